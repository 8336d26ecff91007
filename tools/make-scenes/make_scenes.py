#!/usr/bin/env python3
"""rtpbr-make-scenes: generates the bundled glTF 2.0 scenes from a description.

    make_scenes.py [--description scenes.json] [--out DIR] [--only NAME ...]

Every scene in the description (scenes.json beside this script) becomes DIR/NAME.gltf with
its geometry in DIR/NAME.bin. Area lights are emissive primitives (emissiveFactor x
KHR_materials_emissive_strength), one-sided (they emit on the side their counter-clockwise
winding faces) unless the material is double-sided. Shapes:

  plane    {size: [w, d]}                     quad in the xz-plane, normal +y
  sphere   {radius, segments?, rings?}        UV sphere
  box      {size: [w, h, d], inward?}         closed box, normals out (or in)
  polygon  {sides, radius, normal?, twist?}   regular convex polygon (triangle fan), facing
           or {vertices: [[x,y,z], ...]}      `normal` (default -y), vertices in order
  rect     {size: [w, h]}                     quad in the xy-plane, normal +z, its UVs the
                                              whole image upright (u right, v down)
  sphere_row  {materials: [...], radius, spacing}      spheres along +x, one per material
  disney_grid {parameters: [...], steps, base: {...}, radius, spacing}
           one row per Disney parameter swept from 0 to 1, the others from `base`

Objects take translation [x, y, z], rotation [x, y, z, w] (a quaternion) and a material
name. Materials: baseColor, metallic, roughness, ior, specularFactor, emissive, strength, doubleSided,
emissiveTexture (the name of one of the scene's pictures), disney (a dict of Burley 2012
parameters, written to extras.rtpbr_disney). A scene's pictures are drawn here and written as
DIR/NAME_PICTURE.png (8-bit sRGB, stored deflate blocks: the bytes depend on no zlib version):
{size: [w, h], fill: [r, g, b], blocks: [{rect: [x0, y0, x1, y1], color: [r, g, b]}, ...]},
colours as sRGB bytes, each block painting pixels x0 <= x < x1, y0 <= y < y1 (y down) over the
ones before it.
Only the Python standard library is used; output is deterministic.
"""
import argparse
import json
import math
import os
import struct
import sys
import zlib


def normalize(v):
    n = math.sqrt(sum(c * c for c in v))
    return [c / n for c in v]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def look_at_quaternion(eye, target, up=(0.0, 1.0, 0.0)):
    """Rotation that turns the glTF camera's -z towards target, +y towards up."""
    f = normalize(sub(target, eye))
    z = [-c for c in f]
    x = normalize(cross(up, z))
    y = cross(z, x)
    m = [[x[0], y[0], z[0]], [x[1], y[1], z[1]], [x[2], y[2], z[2]]]  # columns x, y, z
    tr = m[0][0] + m[1][1] + m[2][2]
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        q = [(m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, 0.25 * s]
    elif m[0][0] > m[1][1] and m[0][0] > m[2][2]:
        s = math.sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]) * 2
        q = [0.25 * s, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s, (m[2][1] - m[1][2]) / s]
    elif m[1][1] > m[2][2]:
        s = math.sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]) * 2
        q = [(m[0][1] + m[1][0]) / s, 0.25 * s, (m[1][2] + m[2][1]) / s, (m[0][2] - m[2][0]) / s]
    else:
        s = math.sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]) * 2
        q = [(m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, 0.25 * s, (m[1][0] - m[0][1]) / s]
    return normalize(q)


# ---- shapes: each returns (positions, normals, texcoords, indices) -------------------------

def shape_plane(size):
    w, d = size[0] / 2.0, size[1] / 2.0
    pos = [[-w, 0, -d], [-w, 0, d], [w, 0, d], [w, 0, -d]]
    nrm = [[0, 1, 0]] * 4
    uv = [[0, 0], [0, 1], [1, 1], [1, 0]]
    return pos, nrm, uv, [0, 1, 2, 0, 2, 3]


def shape_sphere(radius, segments=48, rings=24):
    pos, nrm, uv, idx = [], [], [], []
    for r in range(rings + 1):
        theta = math.pi * r / rings
        for s in range(segments + 1):
            phi = 2 * math.pi * s / segments
            n = [math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi)]
            pos.append([radius * c for c in n])
            nrm.append(n)
            uv.append([s / segments, r / rings])
    stride = segments + 1
    for r in range(rings):
        for s in range(segments):
            a, b = r * stride + s, (r + 1) * stride + s
            if r != 0:
                idx += [a, b, a + 1]
            if r != rings - 1:
                idx += [a + 1, b, b + 1]
    return pos, nrm, uv, idx


def shape_box(size, inward=False):
    hx, hy, hz = size[0] / 2.0, size[1] / 2.0, size[2] / 2.0
    faces = [  # normal, tangent u, tangent v (u x v = normal)
        ([1, 0, 0], [0, 0, -1], [0, 1, 0]), ([-1, 0, 0], [0, 0, 1], [0, 1, 0]),
        ([0, 1, 0], [1, 0, 0], [0, 0, -1]), ([0, -1, 0], [1, 0, 0], [0, 0, 1]),
        ([0, 0, 1], [1, 0, 0], [0, 1, 0]), ([0, 0, -1], [-1, 0, 0], [0, 1, 0]),
    ]
    pos, nrm, uv, idx = [], [], [], []
    for n, u, v in faces:
        base = len(pos)
        for (a, b) in [(-1, -1), (1, -1), (1, 1), (-1, 1)]:
            p = [n[i] * (hx, hy, hz)[i] + a * u[i] * (hx, hy, hz)[i] + b * v[i] * (hx, hy, hz)[i] for i in range(3)]
            pos.append(p)
            nrm.append([-c for c in n] if inward else list(n))
            uv.append([(a + 1) / 2, (b + 1) / 2])
        quad = [base, base + 1, base + 2, base, base + 2, base + 3]
        if inward:
            quad = [base, base + 2, base + 1, base, base + 3, base + 2]
        idx += quad
    return pos, nrm, uv, idx


def shape_polygon(obj):
    if "vertices" in obj:
        verts = [list(map(float, v)) for v in obj["vertices"]]
        n = normalize(cross(sub(verts[1], verts[0]), sub(verts[2], verts[0])))
    else:
        sides, radius = int(obj["sides"]), float(obj["radius"])
        n = normalize(obj.get("normal", [0, -1, 0]))
        helper = [0, 0, 1] if abs(n[2]) < 0.9 else [1, 0, 0]
        u = normalize(cross(helper, n))
        v = cross(n, u)  # u x v = n: counter-clockwise seen from the front
        twist = math.radians(obj.get("twist", 0.0))
        verts = []
        for k in range(sides):
            a = twist + 2 * math.pi * k / sides
            verts.append([radius * (math.cos(a) * u[i] + math.sin(a) * v[i]) for i in range(3)])
    pos = verts
    nrm = [n] * len(verts)
    uv = [[0.5, 0.5]] * len(verts)
    idx = []
    for k in range(1, len(verts) - 1):
        idx += [0, k, k + 1]
    return pos, nrm, uv, idx


def shape_rect(size):
    w, h = size[0] / 2.0, size[1] / 2.0
    pos = [[-w, -h, 0], [w, -h, 0], [w, h, 0], [-w, h, 0]]
    nrm = [[0, 0, 1]] * 4
    uv = [[0, 1], [1, 1], [1, 0], [0, 0]]
    return pos, nrm, uv, [0, 1, 2, 0, 2, 3]


# ---- pictures (emission textures) -----------------------------------------------------------

def picture_rows(spec):
    """The picture's rows of RGB bytes, top row first."""
    w, h = int(spec["size"][0]), int(spec["size"][1])
    pixels = [[list(spec.get("fill", [0, 0, 0])) for _ in range(w)] for _ in range(h)]
    for block in spec.get("blocks", []):
        x0, y0, x1, y1 = (int(c) for c in block["rect"])
        for y in range(max(y0, 0), min(y1, h)):
            for x in range(max(x0, 0), min(x1, w)):
                pixels[y][x] = list(block["color"])
    return w, h, [bytes(c for px in row for c in px) for row in pixels]


def png_bytes(width, height, rows):
    """An 8-bit RGB PNG; its zlib stream is stored blocks (no compression), so the file is the
    same bytes wherever it is written."""
    raw = b"".join(b"\0" + row for row in rows)  # filter type 0 on every row
    stream = bytearray(b"\x78\x01")
    for start in range(0, max(len(raw), 1), 65535):
        block = raw[start:start + 65535]
        final = 1 if start + 65535 >= len(raw) else 0
        stream += struct.pack("<BHH", final, len(block), len(block) ^ 0xFFFF) + block
    stream += struct.pack(">I", zlib.adler32(raw))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"sRGB", b"\0") + chunk(b"IDAT", bytes(stream)) + chunk(b"IEND", b""))


# ---- glTF writer ---------------------------------------------------------------------------

class GltfBuilder:
    def __init__(self, name, pictures=None):
        self.name = name
        self.bin = bytearray()
        self.doc = {
            "asset": {"version": "2.0", "generator": "rtpbr-make-scenes"},
            "scene": 0, "scenes": [{"name": name, "nodes": []}],
            "nodes": [], "meshes": [], "materials": [], "accessors": [], "bufferViews": [],
            "buffers": [], "cameras": [],
        }
        self.material_index = {}
        self.mesh_cache = {}
        self.geometry_cache = {}
        self.extensions = set()
        self.pictures = pictures or {}  # picture name -> its spec
        self.texture_index = {}         # picture name -> texture index
        self.png_files = {}             # file name -> bytes

    def texture(self, picture):
        """The texture of one of the scene's pictures (its PNG written beside the .gltf)."""
        if picture in self.texture_index:
            return self.texture_index[picture]
        if picture not in self.pictures:
            raise SystemExit("scene %s: unknown picture %r" % (self.name, picture))
        uri = "%s_%s.png" % (self.name, picture)
        self.png_files[uri] = png_bytes(*picture_rows(self.pictures[picture]))
        doc = self.doc
        if "samplers" not in doc:  # linear filtering, clamped at the picture's edges
            doc["samplers"] = [{"magFilter": 9729, "minFilter": 9729, "wrapS": 33071, "wrapT": 33071}]
        doc.setdefault("images", []).append({"name": picture, "uri": uri})
        doc.setdefault("textures", []).append({"sampler": 0, "source": len(doc["images"]) - 1})
        self.texture_index[picture] = len(doc["textures"]) - 1
        return self.texture_index[picture]

    def _view(self, data, target):
        while len(self.bin) % 4:
            self.bin.append(0)
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data), "target": target})
        self.bin += data
        return len(self.doc["bufferViews"]) - 1

    def _accessor(self, rows, kind, ctype, target, with_bounds=False):
        fmt = {"VEC2": 2, "VEC3": 3, "SCALAR": 1}[kind]
        if ctype == 5126:
            data = b"".join(struct.pack("<%df" % fmt, *r) for r in rows)
        else:
            data = struct.pack("<%dI" % len(rows), *rows)
        acc = {"bufferView": self._view(data, target), "componentType": ctype, "count": len(rows), "type": kind}
        if with_bounds:
            acc["min"] = [min(r[i] for r in rows) for i in range(fmt)]
            acc["max"] = [max(r[i] for r in rows) for i in range(fmt)]
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def material(self, name, spec):
        if name in self.material_index:
            return self.material_index[name]
        m = {"name": name, "pbrMetallicRoughness": {
            "baseColorFactor": list(spec.get("baseColor", [0.8, 0.8, 0.8])) + [1.0],
            "metallicFactor": float(spec.get("metallic", 0.0)),
            "roughnessFactor": float(spec.get("roughness", 0.5))}}
        ext = {}
        if "emissive" in spec:
            m["emissiveFactor"] = list(spec["emissive"])
            strength = float(spec.get("strength", 1.0))
            if strength != 1.0:
                ext["KHR_materials_emissive_strength"] = {"emissiveStrength": strength}
            if "emissiveTexture" in spec:
                m["emissiveTexture"] = {"index": self.texture(spec["emissiveTexture"])}
        if "ior" in spec:
            ext["KHR_materials_ior"] = {"ior": float(spec["ior"])}
        if "specularFactor" in spec:
            ext["KHR_materials_specular"] = {"specularFactor": float(spec["specularFactor"])}
        if "clearcoat" in spec:
            ext["KHR_materials_clearcoat"] = {"clearcoatFactor": float(spec["clearcoat"]),
                                              "clearcoatRoughnessFactor": float(spec.get("clearcoatRoughness", 0.0))}
        if "sheenColor" in spec:
            ext["KHR_materials_sheen"] = {"sheenColorFactor": [float(c) for c in spec["sheenColor"]],
                                          "sheenRoughnessFactor": float(spec.get("sheenRoughness", 0.0))}
        if "anisotropyStrength" in spec:
            ext["KHR_materials_anisotropy"] = {"anisotropyStrength": float(spec["anisotropyStrength"]),
                                               "anisotropyRotation": float(spec.get("anisotropyRotation", 0.0))}
        if ext:
            m["extensions"] = ext
            self.extensions.update(ext.keys())
        if spec.get("doubleSided"):
            m["doubleSided"] = True
        if "disney" in spec:
            m["extras"] = {"rtpbr_disney": spec["disney"]}
        self.doc["materials"].append(m)
        self.material_index[name] = len(self.doc["materials"]) - 1
        return self.material_index[name]

    def mesh(self, key, geometry, material):
        """A mesh of one primitive; meshes of the same geometry share its accessors."""
        cache_key = (key, material)
        if cache_key in self.mesh_cache:
            return self.mesh_cache[cache_key]
        if key not in self.geometry_cache:
            pos, nrm, uv, idx = geometry
            self.geometry_cache[key] = (
                {"POSITION": self._accessor(pos, "VEC3", 5126, 34962, with_bounds=True),
                 "NORMAL": self._accessor(nrm, "VEC3", 5126, 34962),
                 "TEXCOORD_0": self._accessor(uv, "VEC2", 5126, 34962)},
                self._accessor(idx, "SCALAR", 5125, 34963))
        attributes, indices = self.geometry_cache[key]
        prim = {"attributes": dict(attributes), "indices": indices, "material": material}
        self.doc["meshes"].append({"name": key, "primitives": [prim]})
        self.mesh_cache[cache_key] = len(self.doc["meshes"]) - 1
        return self.mesh_cache[cache_key]

    def node(self, name, mesh=None, translation=None, rotation=None, camera=None):
        n = {"name": name}
        if mesh is not None:
            n["mesh"] = mesh
        if camera is not None:
            n["camera"] = camera
        if translation is not None and any(abs(c) > 0 for c in translation):
            n["translation"] = [float(c) for c in translation]
        if rotation is not None:
            n["rotation"] = [float(c) for c in rotation]
        self.doc["nodes"].append(n)
        self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)

    def punctual_light(self, spec):
        """A KHR_lights_punctual light on a node of its own: spec has type (point, spot,
        directional), color, intensity (candela; lux for directional), translation, and for spot
        and directional lights a target the light points at (the node's -Z); optional range, a
        point light's radius (extras.radius) and length (extras.length: a capsule along the
        node's +X, turned by an optional rotation quaternion) and a spot's inner/outer cone
        angles in degrees."""
        light = {"type": spec["type"], "color": [float(c) for c in spec.get("color", [1, 1, 1])],
                 "intensity": float(spec["intensity"])}
        if "range" in spec:
            light["range"] = float(spec["range"])
        if "radius" in spec:  # a point light's sphere (rtpbr reads extras.radius: docs/materials.md)
            light["extras"] = {"radius": float(spec["radius"])}
        if "length" in spec:  # with a radius, a capsule along the node's +X (extras.length)
            light.setdefault("extras", {})["length"] = float(spec["length"])
        if spec["type"] == "spot":
            light["spot"] = {"innerConeAngle": math.radians(spec.get("inner_deg", 0.0)),
                             "outerConeAngle": math.radians(spec.get("outer_deg", 45.0))}
        ext = self.doc.setdefault("extensions", {}).setdefault("KHR_lights_punctual", {"lights": []})
        ext["lights"].append(light)
        self.extensions.add("KHR_lights_punctual")
        t = spec.get("translation", [0.0, 0.0, 0.0])
        q = look_at_quaternion(t, spec["target"], tuple(spec.get("up", (0.0, 1.0, 0.0)))) if "target" in spec else None
        if "rotation" in spec:  # a quaternion (x, y, z, w): a capsule's axis is the node's +X
            q = [float(c) for c in spec["rotation"]]
        self.node(spec.get("name", "light%d" % (len(ext["lights"]) - 1)), translation=t, rotation=q)
        self.doc["nodes"][-1]["extensions"] = {"KHR_lights_punctual": {"light": len(ext["lights"]) - 1}}

    def area_light(self, spec):
        """An EXT_lights_area light (the draft of KhronosGroup/glTF pull request 2525;
        docs/materials.md) on a node of its own: spec has type (disk, rect), color, intensity
        (nits), size (a disk's diameter, a rect's height), a rect's aspect, translation and a
        target the light faces (it emits down the node's -Z)."""
        light = {"type": spec["type"], "color": [float(c) for c in spec.get("color", [1, 1, 1])],
                 "intensity": float(spec["intensity"]), "size": float(spec.get("size", 1.0))}
        if spec["type"] == "rect":
            light["rect"] = {"aspect": float(spec.get("aspect", 1.0))}
        ext = self.doc.setdefault("extensions", {}).setdefault("EXT_lights_area", {"lights": []})
        ext["lights"].append(light)
        self.extensions.add("EXT_lights_area")
        t = spec.get("translation", [0.0, 0.0, 0.0])
        q = look_at_quaternion(t, spec["target"], tuple(spec.get("up", (0.0, 1.0, 0.0))))
        self.node(spec.get("name", "area_light%d" % (len(ext["lights"]) - 1)), translation=t, rotation=q)
        self.doc["nodes"][-1]["extensions"] = {"EXT_lights_area": {"light": len(ext["lights"]) - 1}}

    def camera(self, spec):
        cam = {"type": "perspective", "perspective": {
            "yfov": math.radians(spec.get("yfov_deg", 45.0)), "znear": spec.get("znear", 0.05),
            "zfar": spec.get("zfar", 100.0), "aspectRatio": spec.get("aspect", 4.0 / 3.0)}}
        self.doc["cameras"].append(cam)
        q = look_at_quaternion(spec["eye"], spec["target"], tuple(spec.get("up", (0.0, 1.0, 0.0))))
        self.node("camera%d" % (len(self.doc["cameras"]) - 1), translation=spec["eye"], rotation=q,
                  camera=len(self.doc["cameras"]) - 1)

    def finish(self, out_dir):
        while len(self.bin) % 4:
            self.bin.append(0)
        bin_name = self.name + ".bin"
        self.doc["buffers"] = [{"uri": bin_name, "byteLength": len(self.bin)}]
        if not self.doc["cameras"]:
            del self.doc["cameras"]
        if self.extensions:
            self.doc["extensionsUsed"] = sorted(self.extensions)
        with open(os.path.join(out_dir, bin_name), "wb") as f:
            f.write(self.bin)
        for uri, data in sorted(self.png_files.items()):
            with open(os.path.join(out_dir, uri), "wb") as f:
                f.write(data)
        with open(os.path.join(out_dir, self.name + ".gltf"), "w") as f:
            json.dump(self.doc, f, indent=1, sort_keys=True)
            f.write("\n")


def build_scene(name, spec, out_dir):
    b = GltfBuilder(name, spec.get("pictures"))
    materials = spec.get("materials", {})

    def mat(mname):
        if mname not in materials:
            raise SystemExit("scene %s: unknown material %r" % (name, mname))
        return b.material(mname, materials[mname])

    for cam in spec.get("cameras", []):
        b.camera(cam)
    for light in spec.get("punctual_lights", []):
        b.punctual_light(light)
    for light in spec.get("area_lights", []):
        b.area_light(light)
    for i, obj in enumerate(spec["objects"]):
        shape = obj["shape"]
        label = obj.get("name", "%s%d" % (shape, i))
        t, r = obj.get("translation", [0, 0, 0]), obj.get("rotation")
        if shape == "plane":
            b.node(label, b.mesh("plane%s" % obj["size"], shape_plane(obj["size"]), mat(obj["material"])), t, r)
        elif shape == "rect":
            b.node(label, b.mesh("rect%s" % obj["size"], shape_rect(obj["size"]), mat(obj["material"])), t, r)
        elif shape == "sphere":
            geo = shape_sphere(obj["radius"], obj.get("segments", 48), obj.get("rings", 24))
            b.node(label, b.mesh("sphere%s" % obj["radius"], geo, mat(obj["material"])), t, r)
        elif shape == "box":
            geo = shape_box(obj["size"], obj.get("inward", False))
            b.node(label, b.mesh("box%s%s" % (obj["size"], obj.get("inward", False)), geo, mat(obj["material"])), t, r)
        elif shape == "polygon":
            b.node(label, b.mesh(label, shape_polygon(obj), mat(obj["material"])), t, r)
        elif shape == "sphere_row":
            geo = shape_sphere(obj["radius"])
            n = len(obj["materials"])
            for k, mname in enumerate(obj["materials"]):
                x = t[0] + (k - (n - 1) / 2.0) * obj["spacing"]
                b.node("%s_%s" % (label, mname), b.mesh("sphere%s" % obj["radius"], geo, mat(mname)), [x, t[1], t[2]])
        elif shape == "disney_grid":
            geo = shape_sphere(obj["radius"], 32, 16)
            steps, params = int(obj["steps"]), obj["parameters"]
            for row, p in enumerate(params):
                for k in range(steps):
                    v = k / (steps - 1)
                    disney = dict(obj["base"])
                    disney[p] = v
                    mname = "disney_%s_%.2f" % (p, v)
                    materials[mname] = {"baseColor": disney.get("baseColor", [0.8, 0.8, 0.8]),
                                        "metallic": disney.get("metallic", 0.0),
                                        "roughness": disney.get("roughness", 0.5), "disney": disney}
                    x = t[0] + (k - (steps - 1) / 2.0) * obj["spacing"]
                    y = t[1] + ((len(params) - 1) / 2.0 - row) * obj["spacing"]
                    b.node(mname, b.mesh("sphere%s" % obj["radius"], geo, mat(mname)), [x, y, t[2]])
        else:
            raise SystemExit("scene %s: unknown shape %r" % (name, shape))
    b.finish(out_dir)


def main(argv=None):
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description="Generate rtpbr's bundled glTF scenes.")
    ap.add_argument("--description", default=os.path.join(here, "scenes.json"))
    ap.add_argument("--out", default=os.path.join(here, "..", "..", "samples", "scenes"))
    ap.add_argument("--only", nargs="*", help="scene names to generate (default: all)")
    args = ap.parse_args(argv)
    with open(args.description) as f:
        desc = json.load(f)
    os.makedirs(args.out, exist_ok=True)
    for name, spec in desc["scenes"].items():
        if args.only and name not in args.only:
            continue
        build_scene(name, spec, args.out)
        print("make-scenes: wrote %s" % os.path.join(args.out, name + ".gltf"), file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
