#!/usr/bin/env python3
"""rtpbr-light-assets: writes lit wrappers of the bundled real assets.

    light_assets.py [--spec samples/assets/lights.json] [--assets DIR] [--out DIR]
                    [--only NAME ...] [--print-bounds]

The public glTF sample assets under samples/assets/<Name>/ carry no lights and no camera,
and the engine and the oracle need both. For every asset in the spec this writes
OUT/<Name>/<Name>.lit.gltf: the asset's own JSON unchanged except for

  - one perspective camera (appended to `cameras`) on a new root node looking from `eye` at
    `target` (the glTF camera looks down its node's local -Z, +Y up);
  - one node per added light with `extensions.EXT_lights_area.light`, and the lights in the
    root `extensions.EXT_lights_area.lights` (docs/materials.md, "EXT_lights_area"); a light
    emits down its node's local -Z, so each node's -Z is turned from the light's centre
    towards its `aim`;
  - "EXT_lights_area" in `extensionsUsed` (not in `extensionsRequired`: the asset is still
    meaningful without it);
  - `asset.extras.rtpbr_lit_wrapper`, saying where the file comes from.

An asset whose entry lists `punctual` lights also gets OUT/<Name>/<Name>.punctual.gltf: the
asset's JSON with the same camera, one root node per light with
`extensions.KHR_lights_punctual.light`, the lights in the root
`extensions.KHR_lights_punctual.lights` (docs/materials.md, "Punctual lights"),
"KHR_lights_punctual" in `extensionsUsed` and `asset.extras.rtpbr_punctual_wrapper`; no
EXT_lights_area light.

Buffers and images are referenced by the asset's own relative URIs, so the wrappers must sit
beside the asset (OUT defaults to the assets folder).

The camera is given in the asset's world coordinates: `eye`, `target`, `yfov_deg` and
`aspect` (width / height). Lights are placed relative to the asset's bounding box (the
world-space box of every mesh's POSITION accessor min/max under its node transforms in the
default scene): a light's `offset` is its centre's displacement from the box centre in
units of the box diagonal, `aim` (default [0, 0, 0], the box centre) is the point it faces,
in the same units; `size` (its height, along local Y) is a fraction of the box diagonal;
`aspect` is width / height. `radiance` is linear RGB in the renderers' radiance unit (nits,
docs/materials.md): it is written as color = radiance / max(radiance),
intensity = max(radiance).

A punctual light has a `type` (point, spot, directional), an `offset` (and, for a spot or a
directional light, an `aim`: a directional light shines from offset towards aim; a point light
node gets no rotation) and an `intensity`, linear RGB written as color = intensity /
max(intensity), intensity = max. A point or spot light's intensity is given in candela per
squared box diagonal and written times diagonal^2: the irradiance of a point light is I / d^2
and the distances scale with the box, so one value gives the same irradiance, max / k^2 at a
box-centre distance of k diagonals, on an asset of any size. A directional light's intensity
is lux, written as given. `range` (optional, point and spot) is in box diagonals; a spot's
`inner_deg` and `outer_deg` (default 0 and 45) are its cone angles in degrees.

Only the Python standard library is used; output is deterministic (same spec and asset,
same bytes).
"""
import argparse
import json
import math
import os
import sys

SPEC_DEFAULT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "samples", "assets",
                            "lights.json")
WRAPPER_NOTE = ("Lit wrapper written by tools/assets/light_assets.py from samples/assets/lights.json: "
                "the asset as published plus an added camera and EXT_lights_area lights.")
PUNCTUAL_NOTE = ("Punctual wrapper written by tools/assets/light_assets.py from samples/assets/lights.json: "
                 "the asset as published plus an added camera and KHR_lights_punctual lights.")


# ---- small vector and matrix helpers (column-major 4x4 as in glTF) --------------------

def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def normalize(v):
    n = math.sqrt(sum(c * c for c in v))
    if n == 0.0:
        raise ValueError("zero-length vector")
    return [c / n for c in v]


def mat_mul(a, b):
    """a * b for column-major 4x4 lists of 16."""
    return [sum(a[k * 4 + r] * b[c * 4 + k] for k in range(4)) for c in range(4) for r in range(4)]


def node_matrix(node):
    if "matrix" in node:
        return [float(x) for x in node["matrix"]]
    t = node.get("translation", [0.0, 0.0, 0.0])
    x, y, z, w = node.get("rotation", [0.0, 0.0, 0.0, 1.0])
    s = node.get("scale", [1.0, 1.0, 1.0])
    r = [1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w),
         2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
         2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)]
    return [r[0] * s[0], r[1] * s[0], r[2] * s[0], 0.0,
            r[3] * s[1], r[4] * s[1], r[5] * s[1], 0.0,
            r[6] * s[2], r[7] * s[2], r[8] * s[2], 0.0,
            t[0], t[1], t[2], 1.0]


def transform_point(m, p):
    return [m[0] * p[0] + m[4] * p[1] + m[8] * p[2] + m[12],
            m[1] * p[0] + m[5] * p[1] + m[9] * p[2] + m[13],
            m[2] * p[0] + m[6] * p[1] + m[10] * p[2] + m[14]]


def quaternion_facing(position, aim, up_hint=(0.0, 1.0, 0.0)):
    """Rotation [x, y, z, w] that turns local -Z from position towards aim, local +Y as close
    to up_hint as it can be (world +Z when the direction is vertical)."""
    z = normalize(sub(position, aim))  # local +Z points away from what the node faces
    if abs(sum(a * b for a, b in zip(z, up_hint))) > 0.999:
        up_hint = (0.0, 0.0, 1.0)
    x = normalize(cross(up_hint, z))
    y = cross(z, x)
    m00, m01, m02 = x[0], y[0], z[0]
    m10, m11, m12 = x[1], y[1], z[1]
    m20, m21, m22 = x[2], y[2], z[2]
    tr = m00 + m11 + m22
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        q = [(m21 - m12) / s, (m02 - m20) / s, (m10 - m01) / s, 0.25 * s]
    elif m00 > m11 and m00 > m22:
        s = math.sqrt(1.0 + m00 - m11 - m22) * 2
        q = [0.25 * s, (m01 + m10) / s, (m02 + m20) / s, (m21 - m12) / s]
    elif m11 > m22:
        s = math.sqrt(1.0 + m11 - m00 - m22) * 2
        q = [(m01 + m10) / s, 0.25 * s, (m12 + m21) / s, (m02 - m20) / s]
    else:
        s = math.sqrt(1.0 + m22 - m00 - m11) * 2
        q = [(m02 + m20) / s, (m12 + m21) / s, 0.25 * s, (m10 - m01) / s]
    if q[3] < 0:
        q = [-c for c in q]
    return normalize(q)


def rounded(v, digits=6):
    """Rounds so the written numbers do not carry float noise; -0.0 becomes 0.0."""
    if isinstance(v, list):
        return [rounded(c, digits) for c in v]
    r = round(float(v), digits)
    return 0.0 if r == 0.0 else r


# ---- the asset's bounding box ---------------------------------------------------------

def world_bounds(doc):
    """World-space AABB of every mesh's POSITION accessor box in the default scene."""
    lo = [math.inf] * 3
    hi = [-math.inf] * 3
    scene = doc.get("scenes", [{}])[doc.get("scene", 0)] if doc.get("scenes") else {"nodes": []}
    stack = [(n, [1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0]) for n in scene.get("nodes", [])]
    while stack:
        index, parent = stack.pop()
        node = doc["nodes"][index]
        m = mat_mul(parent, node_matrix(node))
        if "mesh" in node:
            for prim in doc["meshes"][node["mesh"]]["primitives"]:
                acc = doc["accessors"][prim["attributes"]["POSITION"]]
                a, b = acc["min"], acc["max"]
                for i in range(8):
                    corner = [b[k] if (i >> k) & 1 else a[k] for k in range(3)]
                    p = transform_point(m, corner)
                    lo = [min(u, v) for u, v in zip(lo, p)]
                    hi = [max(u, v) for u, v in zip(hi, p)]
        stack.extend((c, m) for c in node.get("children", []))
    if lo[0] == math.inf:
        raise ValueError("no mesh in the default scene")
    return lo, hi


def box_relative(lo, hi, offset):
    """The box centre displaced by offset, in units of the box diagonal."""
    diagonal = math.sqrt(sum((h - l) ** 2 for l, h in zip(lo, hi)))
    return [(l + h) * 0.5 + o * diagonal for l, h, o in zip(lo, hi, offset)]


# ---- the wrappers ---------------------------------------------------------------------

def wrapper_base(doc, spec, note_key, note):
    """A deep copy of the asset with the camera of `spec` (camera 0 of its scene, on a new root
    node) and the note in `asset.extras`; returns it, the scene's root node list, the nodes and
    the asset's box (lo, hi, diagonal)."""
    lo, hi = world_bounds(doc)
    diagonal = math.sqrt(sum((h - l) ** 2 for l, h in zip(lo, hi)))
    out = json.loads(json.dumps(doc))  # a deep copy that keeps key order
    nodes = out.setdefault("nodes", [])
    scene_index = out.get("scene", 0)
    if "scenes" not in out:
        out["scenes"] = [{"nodes": []}]
        out["scene"] = 0
        scene_index = 0
    root = out["scenes"][scene_index].setdefault("nodes", [])

    cam = spec["camera"]
    eye = [float(c) for c in cam["eye"]]
    target = [float(c) for c in cam["target"]]
    distance = math.sqrt(sum(c * c for c in sub(eye, target)))
    cameras = out.setdefault("cameras", [])
    cameras.append({
        "name": "rtpbr_camera",
        "type": "perspective",
        "perspective": {
            "aspectRatio": rounded(cam.get("aspect", 4.0 / 3.0)),
            "yfov": rounded(math.radians(cam.get("yfov_deg", 40.0))),
            "znear": rounded(max(distance - diagonal, diagonal * 1e-3) * 0.5, 4),
            "zfar": rounded((distance + diagonal) * 4.0, 4),
        },
    })
    root.append(len(nodes))
    nodes.append({"name": "rtpbr_camera", "camera": len(cameras) - 1,
                  "translation": rounded(eye), "rotation": rounded(quaternion_facing(eye, target))})
    out["asset"].setdefault("extras", {})[note_key] = note
    return out, root, nodes, (lo, hi, diagonal)


def add_light_node(root, nodes, name, extension, index, position, aim=None):
    """A root node for light `index` of `extension` at `position`, its local -Z turned towards
    `aim` (no rotation when aim is None: a point light shines every way)."""
    node = {"name": "rtpbr_light_" + name, "translation": rounded(position)}
    if aim is not None:
        node["rotation"] = rounded(quaternion_facing(position, aim))
    node["extensions"] = {extension: {"light": index}}
    root.append(len(nodes))
    nodes.append(node)


def color_and_intensity(name, rgb):
    """Linear RGB split into the glTF pair: color = rgb / max(rgb), intensity = max(rgb)."""
    rgb = [float(c) for c in rgb]
    intensity = max(rgb)
    if intensity <= 0.0:
        raise ValueError("light %s: its colour must have a positive component" % name)
    return [c / intensity for c in rgb], intensity


def use_extension(out, extension, lights):
    out.setdefault("extensions", {})[extension] = {"lights": lights}
    used = out.setdefault("extensionsUsed", [])
    if extension not in used:
        used.append(extension)


def lit_wrapper(doc, spec):
    out, root, nodes, (lo, hi, diagonal) = wrapper_base(doc, spec, "rtpbr_lit_wrapper", WRAPPER_NOTE)
    lights = []
    for light in spec["lights"]:
        color, intensity = color_and_intensity(light["name"], light["radiance"])
        entry = {"name": light["name"], "type": "rect",
                 "color": rounded(color),
                 "intensity": rounded(intensity),
                 "size": rounded(light["size"] * diagonal),
                 "rect": {"aspect": rounded(light.get("aspect", 1.0))}}
        position = box_relative(lo, hi, light["offset"])
        aim = box_relative(lo, hi, light.get("aim", [0.0, 0.0, 0.0]))
        add_light_node(root, nodes, light["name"], "EXT_lights_area", len(lights), position, aim)
        lights.append(entry)
    use_extension(out, "EXT_lights_area", lights)
    return out, (lo, hi)


def punctual_wrapper(doc, spec):
    """The asset with the camera and the KHR_lights_punctual lights of spec["punctual"]."""
    out, root, nodes, (lo, hi, diagonal) = wrapper_base(doc, spec, "rtpbr_punctual_wrapper", PUNCTUAL_NOTE)
    lights = []
    for light in spec["punctual"]:
        kind = light["type"]
        if kind not in ("point", "spot", "directional"):
            raise ValueError("punctual light %s: type %r (point, spot or directional)" % (light["name"], kind))
        color, intensity = color_and_intensity(light["name"], light["intensity"])
        if kind != "directional":
            intensity *= diagonal * diagonal  # candela per squared diagonal: irradiance I / d^2 scales with the box
        entry = {"name": light["name"], "type": kind, "color": rounded(color), "intensity": rounded(intensity)}
        if "range" in light:
            if kind == "directional":
                raise ValueError("punctual light %s: a directional light has no range" % light["name"])
            entry["range"] = rounded(light["range"] * diagonal)
        if kind == "spot":
            inner, outer = light.get("inner_deg", 0.0), light.get("outer_deg", 45.0)
            if not 0.0 <= inner < outer <= 90.0:
                raise ValueError("spot light %s: needs 0 <= inner_deg < outer_deg <= 90" % light["name"])
            entry["spot"] = {"innerConeAngle": rounded(math.radians(inner)),
                             "outerConeAngle": rounded(math.radians(outer))}
        position = box_relative(lo, hi, light["offset"])
        aim = None if kind == "point" else box_relative(lo, hi, light.get("aim", [0.0, 0.0, 0.0]))
        add_light_node(root, nodes, light["name"], "KHR_lights_punctual", len(lights), position, aim)
        lights.append(entry)
    use_extension(out, "KHR_lights_punctual", lights)
    return out, (lo, hi)


def write_json(path, doc):
    with open(path, "w", encoding="utf-8", newline="\n") as f:
        json.dump(doc, f, indent=1, ensure_ascii=False)
        f.write("\n")
    print("wrote", path, file=sys.stderr)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--spec", default=SPEC_DEFAULT, help="the lights and cameras (default: %(default)s)")
    ap.add_argument("--assets", help="folder of the assets (default: the spec's folder)")
    ap.add_argument("--out", help="where <Name>/<Name>.lit.gltf go (default: the assets folder)")
    ap.add_argument("--only", nargs="*", help="only these assets")
    ap.add_argument("--print-bounds", action="store_true", help="print each asset's bounding box")
    args = ap.parse_args(argv)
    with open(args.spec, encoding="utf-8") as f:
        spec = json.load(f)
    assets = args.assets or os.path.dirname(os.path.abspath(args.spec))
    out_root = args.out or assets
    for name, entry in sorted(spec["assets"].items()):
        if args.only and name not in args.only:
            continue
        src = os.path.join(assets, name, entry.get("source", name + ".gltf"))
        with open(src, encoding="utf-8") as f:
            doc = json.load(f)
        lit, (lo, hi) = lit_wrapper(doc, entry)
        if args.print_bounds:
            print("%s: min %s max %s" % (name, rounded(lo, 4), rounded(hi, 4)))
        out_dir = os.path.join(out_root, name)
        os.makedirs(out_dir, exist_ok=True)
        write_json(os.path.join(out_dir, name + ".lit.gltf"), lit)
        if "punctual" in entry:
            write_json(os.path.join(out_dir, name + ".punctual.gltf"), punctual_wrapper(doc, entry)[0])
    return 0


if __name__ == "__main__":
    sys.exit(main())
