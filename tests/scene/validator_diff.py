#!/usr/bin/env python3
"""Differential test of the scene loader against the Khronos glTF Validator (issue 18).

    validator_diff.py LOAD_EACH VALIDATE_BATCH_JS OUT_DIR [--count N] [--seed S]

Generates a deterministic corpus (seeded) of mutated glTF files from a few valid base
documents: values replaced by values of other types or out of range, properties removed or
added, array elements duplicated or dropped, node hierarchies rewired, GLB chunk tables
altered. Every file is validated by the Khronos validator (one node process) and loaded by
the loader (one process, LOAD_EACH = scene_load_each). The contract:

    the validator reports an error   =>  the loader refuses the file;
    the validator reports no error   =>  the loader loads it.

A disagreement fails the test unless it is one of the exceptions below, each with its
reason. The counts of agreements and of each exception are printed, so that a reader sees
how much of the corpus each exception covers.
"""
import base64
import copy
import json
import os
import random
import struct
import subprocess
import sys
import zlib

# ---- exceptions: (validator error code or loader result, why) ----------------------------

# The validator reports these errors, and the loader loads the file anyway.
ACCEPTED_ERRORS = {
    'EMPTY_ENTITY': 'an empty top-level array ("materials": []) means "none" to every reader; '
                    'the schema\'s minItems 1 is not worth refusing files for',
    'ACCESSOR_MIN_MISMATCH': 'accessor.min/max are hints the loader never reads: it computes bounds '
                             'from the data itself',
    'ACCESSOR_MAX_MISMATCH': 'as ACCESSOR_MIN_MISMATCH',
    'ACCESSOR_ELEMENT_OUT_OF_MIN_BOUND': 'as ACCESSOR_MIN_MISMATCH (data outside the declared min)',
    'ACCESSOR_ELEMENT_OUT_OF_MAX_BOUND': 'as ACCESSOR_MIN_MISMATCH (data outside the declared max)',
    'MESH_PRIMITIVE_POSITION_ACCESSOR_WITHOUT_BOUNDS': 'as ACCESSOR_MIN_MISMATCH: POSITION min/max are '
                                                       'required by the spec but never read here',
    'NODE_MATRIX_NON_TRS': 'a matrix the validator cannot decompose into T, R, S (zero or sheared '
                           'columns) is used as given: nothing here animates nodes, so no decomposition is '
                           'needed (a last row other than 0,0,0,1 is refused)',
    'ACCESSOR_VECTOR3_NON_UNIT': 'normals (and tangents) are renormalised, and repaired when zero, with a '
                                 'warning',
    'ACCESSOR_NON_UNIT': 'as ACCESSOR_VECTOR3_NON_UNIT',
    'NODE_WEIGHTS_INVALID': 'morph targets and weights are ignored (with a warning)',
    'ACCESSOR_INDEX_TRIANGLE_DEGENERATE': 'degenerate triangles are dropped with a warning '
                                          '(docs: "degenerate triangles removed")',
}

# The validator reports no error, and the loader refuses the file with this result and a
# message containing this text.
REFUSED_CLEAN = {
    ('RTPBR_GLTF_ERROR_NONFINITE', ''): 'finite JSON numbers that overflow a float (1e39), or transforms that '
                                         'make a world position or camera overflow: the outputs are floats '
                                         '(docs/limits.md, "numbers")',
    ('RTPBR_GLTF_ERROR_INVALID_JSON', 'needs 0 < yfov < pi'): 'a camera neither renderer can project '
                                                               '(yfov >= pi; the validator only warns)',
    ('RTPBR_GLTF_ERROR_INVALID_JSON', '/type: value not allowed'): 'a camera of unknown type: neither renderer '
                                                                   'could use it (the validator only warns)',
    ('RTPBR_GLTF_ERROR_INVALID_JSON', 'invalid bufferView'): 'tinygltf 2.7 refuses an accessor without '
                                                             'bufferView used for indices (glTF: all zeros)',
    ('RTPBR_GLTF_ERROR_IMAGE_DECODE', ''): 'an image neither PNG nor JPEG, or truncated: nothing can be '
                                            'textured from it (the validator only warns: '
                                            'IMAGE_UNRECOGNIZED_FORMAT)',
    ('RTPBR_GLTF_ERROR_UNSUPPORTED', 'hierarchy deeper than'): 'the documented node depth limit of 256 levels '
                                                                '(RTPBR_GLTF_MAX_NODE_DEPTH; the walk recurses)',
}


def refusal_excused(result, message):
    for (r, text), why in REFUSED_CLEAN.items():
        if r == result and text in message:
            return (r, text), why
    return None, None


def pad4(b, fill=b'\0'):
    return b + fill * (-len(b) % 4)


def png_bytes(w, h):
    rows = b''.join(b'\0' + b''.join(bytes([(x * 40) % 256, (y * 40) % 256, 128, 255]) for x in range(w))
                    for y in range(h))

    def chunk(kind, data):
        return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data))
    return (b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 6, 0, 0, 0)) +
            chunk(b'IDAT', zlib.compress(rows)) + chunk(b'IEND', b''))


def data_uri(mime, data):
    return 'data:%s;base64,%s' % (mime, base64.b64encode(data).decode())


def base_documents():
    """Valid documents, each (name, json dict, bin bytes or None for data: URIs)."""
    pos = struct.pack('<12f', -1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1)
    nrm = struct.pack('<12f', *([0, 1, 0] * 4))
    uv = struct.pack('<8f', 0, 0, 1, 0, 1, 1, 0, 1)
    idx = struct.pack('<6H', 0, 2, 1, 0, 3, 2)
    buf = pos + nrm + uv + pad4(idx)
    views = [
        {'buffer': 0, 'byteOffset': 0, 'byteLength': 48, 'target': 34962},
        {'buffer': 0, 'byteOffset': 48, 'byteLength': 48, 'target': 34962},
        {'buffer': 0, 'byteOffset': 96, 'byteLength': 32, 'target': 34962},
        {'buffer': 0, 'byteOffset': 128, 'byteLength': 12, 'target': 34963},
    ]
    accessors = [
        {'bufferView': 0, 'componentType': 5126, 'count': 4, 'type': 'VEC3', 'min': [-1, 0, -1], 'max': [1, 0, 1]},
        {'bufferView': 1, 'componentType': 5126, 'count': 4, 'type': 'VEC3'},
        {'bufferView': 2, 'componentType': 5126, 'count': 4, 'type': 'VEC2'},
        {'bufferView': 3, 'componentType': 5123, 'count': 6, 'type': 'SCALAR'},
    ]
    mesh = {'primitives': [{'attributes': {'POSITION': 0, 'NORMAL': 1, 'TEXCOORD_0': 2}, 'indices': 3,
                            'material': 0, 'mode': 4}]}
    plain = {
        'asset': {'version': '2.0', 'generator': 'validator_diff.py'},
        'scene': 0,
        'scenes': [{'nodes': [0, 1]}],
        'nodes': [
            {'mesh': 0, 'translation': [0, 0, 0], 'rotation': [0, 0, 0, 1], 'scale': [1, 1, 1], 'children': [2]},
            {'camera': 0, 'translation': [0, 1, 4], 'name': 'camera'},
            {'mesh': 0, 'matrix': [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 1, 0, 1]},
        ],
        'cameras': [{'type': 'perspective', 'perspective': {'yfov': 0.8, 'znear': 0.1, 'zfar': 100,
                                                            'aspectRatio': 1.5}}],
        'meshes': [mesh],
        'materials': [{'pbrMetallicRoughness': {'baseColorFactor': [0.8, 0.8, 0.8, 1], 'metallicFactor': 0,
                                                'roughnessFactor': 0.5},
                       'emissiveFactor': [0, 0, 0], 'doubleSided': False, 'alphaMode': 'OPAQUE'}],
        'accessors': accessors,
        'bufferViews': views,
        'buffers': [{'byteLength': len(buf), 'uri': data_uri('application/octet-stream', buf)}],
    }
    textured = copy.deepcopy(plain)
    textured['materials'][0]['pbrMetallicRoughness']['baseColorTexture'] = {'index': 0, 'texCoord': 0}
    textured['materials'][0]['normalTexture'] = {'index': 1, 'scale': 1}
    textured['materials'][0]['emissiveTexture'] = {'index': 0}
    textured['materials'][0]['emissiveFactor'] = [1, 1, 1]
    textured['textures'] = [{'source': 0, 'sampler': 0}, {'source': 1}]
    textured['samplers'] = [{'magFilter': 9729, 'minFilter': 9987, 'wrapS': 10497, 'wrapT': 33071}]
    textured['images'] = [{'uri': data_uri('image/png', png_bytes(4, 4))},
                          {'uri': data_uri('image/png', png_bytes(2, 2))}]
    # GLB: the same scene with its buffer and one image in the BIN chunk.
    glb = copy.deepcopy(textured)
    png = png_bytes(4, 4)
    binary = pad4(buf) + pad4(png)
    glb['buffers'] = [{'byteLength': len(binary)}]
    glb['bufferViews'].append({'buffer': 0, 'byteOffset': len(pad4(buf)), 'byteLength': len(png)})
    glb['images'][0] = {'bufferView': 4, 'mimeType': 'image/png'}
    return [('plain', plain, None), ('textured', textured, None), ('glb', glb, binary)]


# ---- mutations -----------------------------------------------------------------------------

REPLACEMENTS = ['NaN', None, {}, [], True, False, 4294967296, -1, 0, 1, 2, 0.5, -0.5, 1e39, -1e39, 1e19, 'yes',
                '0', 5126, 34963, 9729, 'VEC3', 'perspective', [0, 0, 0], [1, 2], [0, 0, 0, 1], {'index': 0},
                1e-30, 100000, 3.14159]
KEYS = ['mesh', 'camera', 'children', 'skin', 'matrix', 'scale', 'translation', 'rotation', 'weights', 'sampler',
        'source', 'index', 'texCoord', 'bufferView', 'byteOffset', 'byteStride', 'count', 'componentType',
        'normalized', 'type', 'sparse', 'indices', 'material', 'mode', 'targets', 'extensionsRequired',
        'extensionsUsed', 'doubleSided', 'alphaCutoff', 'alphaMode', 'uri', 'mimeType', 'yfov', 'znear']


def paths(node, prefix=()):
    """Every (container, key) pair reachable in the document, except inside data: URIs."""
    out = []
    if isinstance(node, dict):
        for k, v in node.items():
            out.append((prefix, node, k))
            out.extend(paths(v, prefix + (k,)))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            out.append((prefix, node, i))
            out.extend(paths(v, prefix + (i,)))
    return out


def mutate(doc, rng):
    kind = rng.choice(['replace', 'replace', 'replace', 'delete', 'add', 'array', 'tree', 'tree'])
    if kind == 'tree':
        try:
            return tree_mutation(doc, rng)
        except (TypeError, KeyError, IndexError, AttributeError):  # an earlier mutation broke the tree
            return 'tree:skipped'
    return value_mutation(doc, rng, kind)


def tree_mutation(doc, rng):
    if True:
        nodes = doc.setdefault('nodes', [])
        n = len(nodes)
        op = rng.choice(['share', 'root_child', 'cycle', 'self', 'scene_dup', 'new_child', 'deep'])
        if op == 'share' and n >= 3:
            nodes[1].setdefault('children', []).append(2)
        elif op == 'root_child':
            doc['scenes'][0]['nodes'].append(2)
        elif op == 'cycle':
            nodes[2].setdefault('children', []).append(0)
        elif op == 'self':
            nodes[2].setdefault('children', []).append(2)
        elif op == 'scene_dup':
            doc['scenes'][0]['nodes'].append(0)
        elif op == 'new_child':
            nodes.append({'mesh': 0, 'scale': rng.choice([[0, 0, 0], [1, 1, 1], [2, 0.5, 1]])})
            nodes[0]['children'].append(len(nodes) - 1)
        else:  # a chain of 250..260 levels under node 2
            depth = rng.randint(250, 260)
            parent = 2
            for _ in range(depth):
                nodes.append({})
                nodes[parent].setdefault('children', []).append(len(nodes) - 1)
                parent = len(nodes) - 1
            nodes[parent]['mesh'] = 0
        return 'tree:' + op


def value_mutation(doc, rng, kind):
    candidates = [p for p in paths(doc) if not (isinstance(p[1], dict) and p[2] == 'uri')]
    prefix, container, key = rng.choice(candidates)
    where = '/'.join(str(x) for x in prefix + (key,))
    if kind == 'replace':
        container[key] = copy.deepcopy(rng.choice(REPLACEMENTS))
    elif kind == 'delete':
        del container[key]
    elif kind == 'add':
        target = container[key] if isinstance(container[key], dict) else container
        if not isinstance(target, dict):
            return value_mutation(doc, rng, 'replace')
        target[rng.choice(KEYS)] = copy.deepcopy(rng.choice(REPLACEMENTS))
    else:
        arr = container[key] if isinstance(container[key], list) else None
        if not arr:
            return value_mutation(doc, rng, 'replace')
        if rng.random() < 0.5:
            arr.append(copy.deepcopy(rng.choice(arr)))
        else:
            arr.pop(rng.randrange(len(arr)))
    return kind + ':' + where


def glb_bytes(doc, binary, rng, mutate_chunks):
    text = pad4(json.dumps(doc).encode(), b' ')
    chunks = [(0x4E4F534A, text)]
    if binary is not None:
        chunks.append((0x004E4942, pad4(binary)))
    note = ''
    if mutate_chunks:
        op = rng.choice(['unknown_after', 'unknown_second', 'unaligned', 'second_json', 'bin_late'])
        note = 'glb:' + op
        if op == 'unknown_after':
            chunks.append((0x5A595858, b'\0' * 8))
        elif op == 'unknown_second':
            chunks.insert(1, (0x5A595858, b'\0' * 12))
        elif op == 'unaligned':
            chunks.append((0x5A595858, b'\0' * 5))
        elif op == 'second_json':
            chunks.append((0x4E4F534A, b'{}  '))
        else:
            chunks.insert(1, (0x5A595858, b'\0' * 4))
    body = b''.join(struct.pack('<II', len(d), t) + d for t, d in chunks)
    return struct.pack('<4sII', b'glTF', 2, 12 + len(body)) + body, note


def main():
    args = sys.argv[1:]
    if len(args) < 3:
        print(__doc__)
        return 2
    load_each, validate_js, out_dir = args[:3]
    count, seed = 300, 18
    if '--count' in args:
        count = int(args[args.index('--count') + 1])
    if '--seed' in args:
        seed = int(args[args.index('--seed') + 1])
    rng = random.Random(seed)
    os.makedirs(out_dir, exist_ok=True)
    bases = base_documents()
    files, notes = [], {}
    for i in range(count):
        name, doc, binary = bases[i % len(bases)]
        doc = copy.deepcopy(doc)
        steps = [mutate(doc, rng) for _ in range(rng.choice([1, 1, 1, 2]))]
        if binary is not None:
            data, note = glb_bytes(doc, binary, rng, rng.random() < 0.25)
            if note:
                steps.append(note)
            path = os.path.join(out_dir, 'm%04d-%s.glb' % (i, name))
            with open(path, 'wb') as f:
                f.write(data)
        else:
            path = os.path.join(out_dir, 'm%04d-%s.gltf' % (i, name))
            with open(path, 'w') as f:
                json.dump(doc, f)
        files.append(path)
        notes[path] = ', '.join(steps)
    for name, doc, binary in bases:  # the bases themselves: clean and loadable
        path = os.path.join(out_dir, 'base-%s.%s' % (name, 'glb' if binary is not None else 'gltf'))
        if binary is not None:
            with open(path, 'wb') as f:
                f.write(glb_bytes(doc, binary, rng, False)[0])
        else:
            with open(path, 'w') as f:
                json.dump(doc, f)
        files.append(path)
        notes[path] = 'unmutated base'

    env = dict(os.environ)
    validated = subprocess.run(['node', validate_js] + files, capture_output=True, text=True, env=env)
    if validated.returncode != 0:
        print('validator failed:', validated.stderr)
        return 1
    verdicts = {}
    for line in validated.stdout.splitlines():
        r = json.loads(line)
        verdicts[r['file']] = r
    loaded = subprocess.run([load_each] + files, capture_output=True, text=True)
    if loaded.returncode != 0:
        print('the loader driver failed:', loaded.returncode, loaded.stderr)
        return 1
    results = {}
    for line in loaded.stdout.splitlines():
        path, result, *message = line.split(' ', 2)
        results[path] = (result, message[0] if message else '')

    agree, excused, failures = 0, {}, []
    crashed = [p for p in files if 'crash' in verdicts[p]]
    for path in crashed:
        print('no verdict: the validator throws on %s [%s]: %s (loader: %s)' %
              (path, notes[path], verdicts[path]['crash'], results[path][0]))
    files = [p for p in files if 'crash' not in verdicts[p]]
    for path in files:
        v, (result, message) = verdicts[path], results[path]
        codes = sorted({e.split(' ')[0] for e in v['errors']})
        loads = result == 'RTPBR_GLTF_SUCCESS'
        if bool(codes) != loads:
            agree += 1
            continue
        if codes:  # validator error, loader loaded
            if all(c in ACCEPTED_ERRORS for c in codes):
                for c in codes:
                    excused[c] = excused.get(c, 0) + 1
                continue
            failures.append('%s [%s]: validator errors %s, the loader loads it' % (path, notes[path], v['errors']))
        else:  # validator clean, loader refused
            key, _ = refusal_excused(result, message)
            if key:
                excused[key] = excused.get(key, 0) + 1
                continue
            failures.append('%s [%s]: validator clean (warnings %s), the loader refuses: %s %s' %
                            (path, notes[path], v['warnings'], result, message))
    refused_by_both = sum(1 for p in files if verdicts[p]['errors'] and results[p][0] != 'RTPBR_GLTF_SUCCESS')
    print('%d files (seed %d): %d agree (%d refused by both, %d loaded by both), %d excused, %d disagree' %
          (len(files), seed, agree, refused_by_both, agree - refused_by_both, sum(excused.values()), len(failures)))
    for k, n in sorted(excused.items(), key=str):
        print('  excused %4d x %s: %s' % (n, k, ACCEPTED_ERRORS.get(k) if isinstance(k, str) else REFUSED_CLEAN[k]))
    for f in failures:
        print('DISAGREE', f)
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
