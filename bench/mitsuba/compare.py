#!/usr/bin/env python3
"""Side-by-side speed comparison of rtpbr-oracle and Mitsuba 3 (scalar_rgb) on quad_light.gltf.

Manual benchmark (not run by CI). Needs `mitsuba` and `numpy` in the running Python, e.g.
    python3 -m venv /tmp/mi && /tmp/mi/bin/pip install mitsuba numpy
    /tmp/mi/bin/python bench/mitsuba/compare.py --oracle build/oracle/rtpbr-oracle
Prints a Markdown table (samples/s of each renderer, ratio) and the image difference.

The Mitsuba scene is rebuilt by hand from samples/scenes/quad_light.gltf (see scene_dict):
floor: 6 x 6 plane at y = 0, glTF metallic copper (base colour (0.955, 0.638, 0.538),
roughness 0.35) -> Mitsuba 'principled' (metallic 1, roughness 0.35, i.e. GGX alpha = 0.35^2,
Schlick F0 = base colour) or, with --bsdf conductor, 'roughconductor' alpha = 0.35^2 with
material 'none' and specular_reflectance = base colour (no Fresnel angle dependence).
light: one-sided square (vertices (+-0.5657, 1.4, +-0.5657), normal -y), radiance 8 x (1, 0.95,
0.9), diffuse 0.8 surface (glTF material of the light). Camera from node 'camera0'.
Both use box pixel filter, independent samples, max depth 16 (the oracle's default).
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time

try:  # --help works without them; main() says they are missing
    import numpy as np
    import mitsuba as mi
    import drjit as dr
except ImportError as e:
    np = mi = dr = None
    missing = e


def quat_rotate(q, v):
    """Rotate vector v by unit quaternion q = (x, y, z, w) (glTF order)."""
    x, y, z, w = q
    u = np.array([x, y, z])
    v = np.asarray(v, dtype=float)
    return 2.0 * np.dot(u, v) * u + (w * w - np.dot(u, u)) * v + 2.0 * w * np.cross(u, v)


def gltf_camera(path):
    with open(path) as f:
        g = json.load(f)
    node = next(n for n in g['nodes'] if n.get('name') == 'camera0')
    cam = g['cameras'][node['camera']]['perspective']
    eye = np.array(node.get('translation', [0, 0, 0]), dtype=float)
    q = node.get('rotation', [0, 0, 0, 1])
    fwd = quat_rotate(q, [0, 0, -1])  # glTF cameras look down -Z, +Y up
    up = quat_rotate(q, [0, 1, 0])
    return eye, eye + fwd, up, math.degrees(cam['yfov'])


def scene_dict(gltf, width, height, max_depth, bsdf):
    eye, target, up, yfov = gltf_camera(gltf)
    T = mi.ScalarTransform4f
    base = [0.955, 0.638, 0.538]
    rough = 0.35
    if bsdf == 'principled':
        floor_bsdf = {'type': 'principled', 'base_color': {'type': 'rgb', 'value': base},
                      'metallic': 1.0, 'roughness': rough}
    else:
        floor_bsdf = {'type': 'roughconductor', 'material': 'none', 'distribution': 'ggx',
                      'alpha': rough * rough, 'specular_reflectance': {'type': 'rgb', 'value': base}}
    return {
        'type': 'scene',
        'integrator': {'type': 'path', 'max_depth': max_depth},
        'sensor': {
            'type': 'perspective', 'fov': yfov, 'fov_axis': 'y',
            'to_world': T().look_at(origin=eye.tolist(), target=target.tolist(), up=up.tolist()),
            'sampler': {'type': 'independent', 'sample_count': 1},
            'film': {'type': 'hdrfilm', 'width': width, 'height': height,
                     'rfilter': {'type': 'box'}, 'pixel_format': 'rgb'},
        },
        # rectangle: [-1,1]^2 in the xy plane, normal +z; rotate about x by -90 -> normal +y.
        'floor': {'type': 'rectangle', 'to_world': T().rotate([1, 0, 0], -90).scale(3.0), 'bsdf': floor_bsdf},
        # rotate by +90 -> normal -y (faces down); side 2 x 0.5657 = 1.131.
        'light': {'type': 'rectangle',
                  'to_world': T().translate([0, 1.4, 0]).rotate([1, 0, 0], 90).scale(0.5656854249492381),
                  'bsdf': {'type': 'diffuse', 'reflectance': {'type': 'rgb', 'value': [0.8, 0.8, 0.8]}},
                  'emitter': {'type': 'area', 'radiance': {'type': 'rgb', 'value': [8.0, 7.6, 7.2]}}},
    }


def run_mitsuba(scene, spp, threads, out):
    dr.set_thread_count(threads)
    mi.render(scene, spp=1)  # warm-up (thread pool, first-use allocations)
    t0 = time.perf_counter()
    img = mi.render(scene, spp=spp, seed=threads)  # distinct seeds -> noise floor
    dt = time.perf_counter() - t0
    mi.util.write_bitmap(out, img, write_async=False)  # async write was lost at exit
    return dt, np.array(img, dtype=np.float64)[..., :3]


def run_oracle(exe, gltf, w, h, spp, threads, out, extra):
    cmd = [exe, gltf, '-o', out, '--width', str(w), '--height', str(h), '--spp', str(spp),
           '--threads', str(threads)] + extra
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit('oracle failed: %s\n%s' % (' '.join(cmd), p.stderr))
    m = re.search(r'samples in ([0-9.]+)s', p.stderr)
    if not m:
        sys.exit('cannot parse oracle stats: ' + p.stderr)
    img = np.array(mi.Bitmap(out).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32), dtype=np.float64)
    return float(m.group(1)), img


def rel_diff(a, b, block=1):
    """Mean over pixels of |a - b| / mean(a, b) on luminance-like channel sums, after averaging
    block x block pixel tiles (block > 1 removes most of the per-pixel Monte Carlo noise)."""
    la, lb = a.sum(axis=2), b.sum(axis=2)
    if block > 1:
        hh, ww = la.shape[0] // block * block, la.shape[1] // block * block
        la = la[:hh, :ww].reshape(hh // block, block, ww // block, block).mean(axis=(1, 3))
        lb = lb[:hh, :ww].reshape(hh // block, block, ww // block, block).mean(axis=(1, 3))
    m = 0.5 * (la + lb)
    mask = m > 1e-3 * m.max()
    return float(np.mean(np.abs(la - lb)[mask] / m[mask]))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.dirname(os.path.dirname(here))
    ap.add_argument('--oracle', default=os.path.join(root, 'build', 'oracle', 'rtpbr-oracle'))
    ap.add_argument('--scene', default=os.path.join(root, 'samples', 'scenes', 'quad_light.gltf'))
    ap.add_argument('--width', type=int, default=320)
    ap.add_argument('--height', type=int, default=240)
    ap.add_argument('--spp', type=int, default=64)
    ap.add_argument('--max-depth', type=int, default=16)
    # One thread count per process: switching dr.set_thread_count between renders in one
    # process hung Mitsuba (sleeping, no CPU) in our run; run the script once per count.
    ap.add_argument('--threads', default='2')
    ap.add_argument('--bsdf', choices=['principled', 'conductor'], default='principled')
    ap.add_argument('--outdir', default=tempfile.mkdtemp(prefix='rtpbr_mitsuba_'))
    a = ap.parse_args()
    if mi is None:
        sys.exit(f"compare.py: {missing} (pip install mitsuba numpy)")
    mi.set_variant('scalar_rgb')
    os.makedirs(a.outdir, exist_ok=True)

    threads = [int(t) for t in a.threads.split(',')]
    t0 = time.perf_counter()
    scene = mi.load_dict(scene_dict(a.scene, a.width, a.height, a.max_depth, a.bsdf))
    load_s = time.perf_counter() - t0
    n = a.width * a.height * a.spp
    rows, imgs = [], {}
    for t in threads:
        for name, extra in [('rtpbr-oracle --single-scatter', ['--single-scatter']),
                            ('rtpbr-oracle (multi-bounce walk)', [])]:
            out = os.path.join(a.outdir, 'oracle_%s_%d.exr' % ('ss' if extra else 'walk', t))
            s, img = run_oracle(a.oracle, a.scene, a.width, a.height, a.spp, t, out,
                                extra + ['--max-depth', str(a.max_depth)])
            rows.append((name, t, s))
            imgs[(name, t)] = img
        out = os.path.join(a.outdir, 'mitsuba_%d.exr' % t)
        s, img = run_mitsuba(scene, a.spp, t, out)
        name = 'Mitsuba %s scalar_rgb path (%s)' % (mi.__version__, a.bsdf)
        rows.append((name, t, s))
        imgs[(name, t)] = img

    print('%d x %d, %d spp, max depth %d, Mitsuba scene load %.2fs (excluded), images in %s\n'
          % (a.width, a.height, a.spp, a.max_depth, load_s, a.outdir))
    print('| renderer | threads | render s | samples/s | Mitsuba time / this time |')
    print('|---|---|---|---|---|')
    mits = {t: s for (nm, t, s) in rows if nm.startswith('Mitsuba')}
    for nm, t, s in rows:
        print('| %s | %d | %.2f | %.0f | %.2f |' % (nm, t, s, n / s, mits[t] / s))
    t = threads[-1]
    mimg = imgs[[k for k in imgs if k[0].startswith('Mitsuba') and k[1] == t][0]]
    print('\nImage difference vs Mitsuba (%d threads), mean |a-b|/mean(a,b) over lit pixels:' % t)
    print('| image | per pixel | 8x8 blocks | mean ratio (this / Mitsuba) |')
    print('|---|---|---|---|')
    for (nm, tt), img in imgs.items():
        if tt != t or nm.startswith('Mitsuba'):
            continue
        print('| %s | %.3f | %.3f | %.3f |' % (nm, rel_diff(img, mimg), rel_diff(img, mimg, 8),
                                              img.sum() / mimg.sum()))
    if len(threads) > 1:
        ma, mb = [imgs[k] for k in imgs if k[0].startswith('Mitsuba')][:2]
        print('| Mitsuba %d vs %d threads (noise floor) | %.3f | %.3f | %.3f |'
              % (threads[0], threads[1], rel_diff(ma, mb), rel_diff(ma, mb, 8), ma.sum() / mb.sum()))


if __name__ == '__main__':
    main()
