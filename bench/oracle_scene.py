#!/usr/bin/env python3
"""Writes bench/oracle_room.gltf: a small closed room (diffuse walls), a ceiling quad light,
a rough gold sphere, a clear-coated Disney sphere and a smooth-ish copper plate. Reproducible:
the file is a pure function of this script. Usage: oracle_scene.py OUT.gltf"""
import base64, json, math, struct, sys

if len(sys.argv) == 2 and sys.argv[1] in ("-h", "--help"):
    print(__doc__)
    sys.exit(0)
if len(sys.argv) != 2 or sys.argv[1].startswith("-"):
    print(__doc__, file=sys.stderr)
    sys.exit(2)

meshes, accessors, views, blob = [], [], [], bytearray()

def add_view(data, target):
    global blob
    while len(blob) % 4:
        blob += b'\0'
    off = len(blob)
    blob += data
    views.append({"buffer": 0, "byteOffset": off, "byteLength": len(data), "target": target})
    return len(views) - 1

def add_mesh(name, pos, nrm, idx, material):
    pv = add_view(b''.join(struct.pack('<3f', *p) for p in pos), 34962)
    nv = add_view(b''.join(struct.pack('<3f', *n) for n in nrm), 34962)
    iv = add_view(b''.join(struct.pack('<I', i) for i in idx), 34963)
    lo = [min(p[k] for p in pos) for k in range(3)]
    hi = [max(p[k] for p in pos) for k in range(3)]
    accessors.append({"bufferView": pv, "componentType": 5126, "count": len(pos), "type": "VEC3", "min": lo, "max": hi})
    accessors.append({"bufferView": nv, "componentType": 5126, "count": len(nrm), "type": "VEC3"})
    accessors.append({"bufferView": iv, "componentType": 5125, "count": len(idx), "type": "SCALAR"})
    a = len(accessors) - 3
    meshes.append({"name": name, "primitives": [{"attributes": {"POSITION": a, "NORMAL": a + 1}, "indices": a + 2, "material": material}]})
    return len(meshes) - 1

def quad(c, u, v, n):
    p = [[c[k] - u[k] - v[k] for k in range(3)], [c[k] + u[k] - v[k] for k in range(3)],
         [c[k] + u[k] + v[k] for k in range(3)], [c[k] - u[k] + v[k] for k in range(3)]]
    return p, [n] * 4, [0, 1, 2, 0, 2, 3]

def sphere(c, r, nu=48, nv=24):
    pos, nrm, idx = [], [], []
    for j in range(nv + 1):
        th = math.pi * j / nv
        for i in range(nu + 1):
            ph = 2 * math.pi * i / nu
            n = [math.sin(th) * math.cos(ph), math.cos(th), -math.sin(th) * math.sin(ph)]
            pos.append([c[k] + r * n[k] for k in range(3)])
            nrm.append(n)
    for j in range(nv):
        for i in range(nu):
            a, b = j * (nu + 1) + i, (j + 1) * (nu + 1) + i
            if j > 0:  # at the poles one of the two triangles is degenerate
                idx += [a, b, a + 1]
            if j < nv - 1:
                idx += [a + 1, b, b + 1]
    return pos, nrm, idx

materials = [
    {"name": "white", "pbrMetallicRoughness": {"baseColorFactor": [0.75, 0.75, 0.75, 1], "metallicFactor": 0, "roughnessFactor": 1}},
    {"name": "red", "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.1, 0.08, 1], "metallicFactor": 0, "roughnessFactor": 1}},
    {"name": "green", "pbrMetallicRoughness": {"baseColorFactor": [0.1, 0.6, 0.12, 1], "metallicFactor": 0, "roughnessFactor": 1}},
    {"name": "light", "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0, "roughnessFactor": 1},
     "emissiveFactor": [1, 1, 1], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 12}}},
    {"name": "gold", "pbrMetallicRoughness": {"baseColorFactor": [1.0, 0.78, 0.34, 1], "metallicFactor": 1, "roughnessFactor": 0.6}},
    {"name": "plastic", "pbrMetallicRoughness": {"baseColorFactor": [0.1, 0.2, 0.6, 1], "metallicFactor": 0, "roughnessFactor": 0.35},
     "extras": {"rtpbr_disney": {"clearcoat": 1.0, "clearcoatGloss": 0.9, "sheen": 0.5, "subsurface": 0.2}}},
    {"name": "copper", "pbrMetallicRoughness": {"baseColorFactor": [0.95, 0.64, 0.54, 1], "metallicFactor": 1, "roughnessFactor": 0.25}},
]
S = 1.0  # room half size: [-1, 1]^3
add_mesh("floor", *quad([0, -S, 0], [S, 0, 0], [0, 0, -S], [0, 1, 0]), 0)
add_mesh("ceiling", *quad([0, S, 0], [S, 0, 0], [0, 0, S], [0, -1, 0]), 0)
add_mesh("back", *quad([0, 0, -S], [S, 0, 0], [0, S, 0], [0, 0, 1]), 0)
add_mesh("left", *quad([-S, 0, 0], [0, 0, S], [0, S, 0], [1, 0, 0]), 1)
add_mesh("right", *quad([S, 0, 0], [0, 0, -S], [0, S, 0], [-1, 0, 0]), 2)
add_mesh("light", *quad([0, S - 0.002, 0], [0.3, 0, 0], [0, 0, 0.3], [0, -1, 0]), 3)
add_mesh("gold", *sphere([-0.42, -0.62, -0.2], 0.38), 4)
add_mesh("plastic", *sphere([0.45, -0.68, 0.25], 0.32), 5)
add_mesh("copper", *quad([0.35, -0.2, -0.9], [0.35, 0, 0], [0, 0.35, 0], [0, 0, 1]), 6)

nodes = [{"mesh": m} for m in range(len(meshes))]
nodes.append({"camera": 0, "translation": [0, 0, 3.4]})
gltf = {
    "asset": {"version": "2.0", "generator": "rtpbr bench/oracle_scene.py"},
    "extensionsUsed": ["KHR_materials_emissive_strength"],
    "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}], "nodes": nodes, "meshes": meshes,
    "materials": materials,
    "cameras": [{"type": "perspective", "perspective": {"yfov": 0.62, "aspectRatio": 1.0, "znear": 0.01}}],
    "accessors": accessors, "bufferViews": views,
    "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}],
}
with open(sys.argv[1], "w") as f:
    json.dump(gltf, f)
