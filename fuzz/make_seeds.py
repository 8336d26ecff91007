#!/usr/bin/env python3
"""Writes the seed corpora of the fuzzers (fuzz/README.md).

  make_seeds.py SAMPLES_DIR ASSETS_DIR OUT_DIR

OUT_DIR/scene: the bundled scenes (samples/scenes/*.gltf, external .bin as shipped), each
also as GLB (BIN chunk) and as .gltf with a data: URI buffer, plus one small scene that uses
every feature the loader reads (textures by file, data: URI and bufferView; all KHR material
extensions; Disney extras; EXT_lights_area rect and disk; KHR_lights_punctual point, spot and
directional; a camera; strips and fans).
OUT_DIR/image: tiny images in the formats rtpbr-diff is used with (PNG 8/16-bit, grey,
alpha; EXR half/float; HDR; JPEG) and a few others OpenImageIO reads, made by oiiotool.
"""
import base64
import json
import os
import shutil
import struct
import subprocess
import sys


def glb(doc, bin_bytes):
    js = json.dumps(doc, separators=(",", ":")).encode()
    js += b" " * (-len(js) % 4)
    chunks = struct.pack("<II", len(js), 0x4E4F534A) + js
    if bin_bytes is not None:
        bin_bytes += b"\0" * (-len(bin_bytes) % 4)
        chunks += struct.pack("<II", len(bin_bytes), 0x004E4942) + bin_bytes
    return struct.pack("<III", 0x46546C67, 2, 12 + len(chunks)) + chunks


def scene_seeds(samples, out):
    for name in sorted(os.listdir(samples)):
        if not name.endswith(".gltf"):
            continue
        stem = name[:-5]
        src = os.path.join(samples, name)
        shutil.copy(src, os.path.join(out, name))
        with open(src) as f:
            doc = json.load(f)
        with open(os.path.join(samples, doc["buffers"][0]["uri"]), "rb") as f:
            data = f.read()
        packed = json.loads(json.dumps(doc))
        del packed["buffers"][0]["uri"]
        with open(os.path.join(out, stem + ".glb"), "wb") as f:
            f.write(glb(packed, data))
        # Inline (data: URI) variants only of small buffers: seeds of 70-95 KB made every
        # mutation of them cost 80-250 ms (issue 18); the data: URI path is the same.
        if len(data) > 4096:
            continue
        inline = json.loads(json.dumps(doc))
        inline["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(data).decode()
        with open(os.path.join(out, stem + "-inline.gltf"), "w") as f:
            json.dump(inline, f, separators=(",", ":"))


def features_seed(assets, out):
    """A quad (indexed), a strip and a fan, with every material feature and every light kind."""
    pos = [-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1]
    nrm = [0, 1, 0] * 4
    uv = [0, 0, 1, 0, 1, 1, 0, 1]
    tan = [1, 0, 0, 1] * 4
    idx = [0, 2, 1, 0, 3, 2]
    strip = [0, 1, 3, 2]
    blob = struct.pack("<12f", *pos) + struct.pack("<12f", *nrm) + struct.pack("<8f", *uv) + \
        struct.pack("<16f", *tan) + struct.pack("<6I", *idx) + struct.pack("<4H", *strip)
    with open(os.path.join(assets, "tex.png"), "rb") as f:
        png = f.read()
    with open(os.path.join(assets, "tex.jpg"), "rb") as f:
        jpg = f.read()
    png_offset = len(blob)
    blob += png + b"\0" * (-len(png) % 4)
    views = [
        {"buffer": 0, "byteOffset": 0, "byteLength": 48},
        {"buffer": 0, "byteOffset": 48, "byteLength": 48},
        {"buffer": 0, "byteOffset": 96, "byteLength": 32},
        {"buffer": 0, "byteOffset": 128, "byteLength": 64},
        {"buffer": 0, "byteOffset": 192, "byteLength": 24},
        {"buffer": 0, "byteOffset": 216, "byteLength": 8},
        {"buffer": 0, "byteOffset": png_offset, "byteLength": len(png)},
    ]
    accessors = [
        {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, 0, -1], "max": [1, 0, 1]},
        {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
        {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
        {"bufferView": 3, "componentType": 5126, "count": 4, "type": "VEC4"},
        {"bufferView": 4, "componentType": 5125, "count": 6, "type": "SCALAR"},
        {"bufferView": 5, "componentType": 5123, "count": 4, "type": "SCALAR"},
    ]
    attrs = {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2, "TANGENT": 3}
    materials = [
        {"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.7, 0.6, 1], "metallicFactor": 0.5,
                                  "roughnessFactor": 0.4, "baseColorTexture": {"index": 0},
                                  "metallicRoughnessTexture": {"index": 1}},
         "normalTexture": {"index": 2, "scale": 0.5}, "emissiveTexture": {"index": 0},
         "alphaMode": "MASK", "alphaCutoff": 0.3, "doubleSided": True,
         "extensions": {"KHR_materials_specular": {"specularFactor": 0.7, "specularColorFactor": [1, 0.9, 0.8]},
                        "KHR_materials_ior": {"ior": 1.45},
                        "KHR_materials_sheen": {"sheenColorFactor": [0.2, 0.3, 0.4], "sheenRoughnessFactor": 0.5},
                        "KHR_materials_clearcoat": {"clearcoatFactor": 0.6, "clearcoatRoughnessFactor": 0.2},
                        "KHR_materials_anisotropy": {"anisotropyStrength": 0.5, "anisotropyRotation": 0.3}}},
        {"emissiveFactor": [1, 0.9, 0.8], "alphaMode": "BLEND",
         "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 5}}},
        {"extras": {"rtpbr_disney": {"baseColor": [0.5, 0.4, 0.3], "metallic": 0.1, "roughness": 0.6,
                                     "subsurface": 0.2, "specular": 0.5, "specularTint": 0.1,
                                     "anisotropic": 0.3, "sheen": 0.4, "sheenTint": 0.5,
                                     "clearcoat": 0.2, "clearcoatGloss": 0.9}}},
    ]
    doc = {
        "asset": {"version": "2.0", "generator": "rtpbr fuzz/make_seeds.py"},
        "extensionsUsed": ["KHR_materials_specular", "KHR_materials_ior", "KHR_materials_sheen",
                           "KHR_materials_clearcoat", "KHR_materials_anisotropy",
                           "KHR_materials_emissive_strength", "EXT_lights_area", "KHR_lights_punctual"],
        "extensions": {"EXT_lights_area": {"lights": [
            {"type": "rect", "color": [1, 1, 0.9], "intensity": 100, "size": 0.5, "rect": {"aspect": 2}},
            {"type": "disk", "color": [0.9, 1, 1], "intensity": 50, "size": 0.3},
            {"shape": "rect", "width": 0.4, "height": 0.2, "luminance": 80, "twoSided": True}]},
                       "KHR_lights_punctual": {"lights": [
            {"type": "point", "color": [1, 0.8, 0.6], "intensity": 20, "range": 8},
            {"type": "spot", "intensity": 40, "spot": {"innerConeAngle": 0.3, "outerConeAngle": 0.7}},
            {"type": "spot"},
            {"type": "directional", "color": [0.9, 0.9, 1], "intensity": 3}]}},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2, 3, 4, 5, 6, 8, 9, 10]}],
        "nodes": [
            {"mesh": 0},
            {"mesh": 1, "translation": [0, 2, 0], "rotation": [1, 0, 0, 0]},
            {"mesh": 2, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 0, 3, 0, 0, 1]},
            {"camera": 0, "translation": [0, 1, 5], "children": [7]},
            {"extensions": {"EXT_lights_area": {"light": 0}}, "translation": [0, 3, 0],
             "rotation": [-0.7071068, 0, 0, 0.7071068]},
            {"extensions": {"EXT_lights_area": {"light": 1}}, "translation": [1, 3, 0], "scale": [2, 2, 2]},
            {"extensions": {"EXT_lights_area": {"light": 2}}, "translation": [-1, 3, 0]},
            {"camera": 1},
            {"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0, 2, 1], "children": [11]},
            {"extensions": {"KHR_lights_punctual": {"light": 1}}, "translation": [2, 3, 0],
             "rotation": [-0.5, 0.5, 0.5, 0.5], "scale": [1, 2, 1]},
            {"extensions": {"KHR_lights_punctual": {"light": 3}}, "rotation": [-0.3826834, 0, 0, 0.9238795]},
            {"extensions": {"KHR_lights_punctual": {"light": 2}}, "translation": [0, 0, -1]},
        ],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "zfar": 100, "aspectRatio": 1.5}},
                    {"type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.01}}],
        "meshes": [
            {"primitives": [{"attributes": attrs, "indices": 4, "material": 0}]},
            {"primitives": [{"attributes": {"POSITION": 0}, "indices": 5, "mode": 5, "material": 1}]},
            {"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 2}, "mode": 6, "material": 2},
                            {"attributes": {"POSITION": 0}, "mode": 0}]},
        ],
        "materials": materials,
        "textures": [{"source": 0, "sampler": 0}, {"source": 1, "sampler": 1}, {"source": 2}],
        "samplers": [{"magFilter": 9728, "wrapS": 33071, "wrapT": 33648}, {"magFilter": 9729}],
        "images": [{"uri": "tex.png"},
                   {"uri": "data:image/jpeg;base64," + base64.b64encode(jpg).decode()},
                   {"bufferView": 6, "mimeType": "image/png"}],
        "bufferViews": views,
        "accessors": accessors,
        "buffers": [{"byteLength": len(blob)}],
    }
    with open(os.path.join(out, "features.glb"), "wb") as f:
        f.write(glb(doc, blob))
    doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(blob).decode()
    with open(os.path.join(out, "features.gltf"), "w") as f:
        json.dump(doc, f, separators=(",", ":"))


def image_seeds(out):
    pattern = ["--pattern", "checker:width=2:height=2:color1=0.9,0.2,0.1:color2=0.1,0.3,0.8", "5x3", "3"]
    grey = ["--pattern", "fill:top=0.1:bottom=0.9", "3x4", "1"]
    rgba = ["--pattern", "fill:color=0.2,0.4,0.6,0.5", "4x2", "4"]
    jobs = [
        (pattern, ["-d", "uint8"], "rgb8.png"),
        (pattern, ["-d", "uint16"], "rgb16.png"),
        (grey, ["-d", "uint8"], "grey8.png"),
        (rgba, ["-d", "uint8"], "rgba8.png"),
        (pattern, ["-d", "half"], "half.exr"),
        (rgba, ["-d", "float", "--compression", "zip"], "float-zip.exr"),
        (pattern, ["-d", "half", "--compression", "piz"], "half-piz.exr"),
        (pattern, ["-d", "half", "--tile", "4", "4"], "tiled.exr"),
        (pattern, [], "rgb.hdr"),
        (pattern, ["-d", "uint8"], "rgb.jpg"),
        (pattern, ["-d", "uint8"], "rgb.tif"),
        (pattern, ["-d", "uint8"], "rgb.bmp"),
        (pattern, ["-d", "uint8"], "rgb.tga"),
        (pattern, ["-d", "uint8"], "rgb.ppm"),
    ]
    for args, opts, name in jobs:
        subprocess.run(["oiiotool", *args, *opts, "-o", os.path.join(out, name)], check=True)


def main():
    if len(sys.argv) == 2 and sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        return
    if len(sys.argv) != 4 or any(a.startswith("-") for a in sys.argv[1:]):
        sys.stderr.write("usage:" + __doc__)
        sys.exit(2)
    samples, assets, out = sys.argv[1:4]
    for sub in ("scene", "image"):
        os.makedirs(os.path.join(out, sub), exist_ok=True)
    scene_seeds(samples, os.path.join(out, "scene"))
    features_seed(assets, os.path.join(out, "scene"))
    image_seeds(os.path.join(out, "image"))


if __name__ == "__main__":
    main()
