#!/usr/bin/env python3
"""rtpbr-render's memory on hostile input (issue 31): a render whose need is over the memory
available or --memory-limit is refused before anything is allocated, with the need in the
message; a scene whose 1x1 PNG inflates to 256 MiB is refused while inflating, and the
program's peak stays within 64 MiB of the same scene with a valid PNG.

usage: cli_memory.py RTPBR_RENDER SCENES_DIR WORKDIR"""
import json
import os
import shutil
import struct
import subprocess
import sys
import zlib

render, scenes, work = sys.argv[1:4]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
failures = []


def run(args):
    """Runs rtpbr-render; returns (exit code, stderr, peak RSS in MiB)."""
    with open(os.path.join(work, 'out.txt'), 'w') as out, open(os.path.join(work, 'err.txt'), 'w') as err:
        p = subprocess.Popen([render] + args, stdout=out, stderr=err)
        _, status, usage = os.wait4(p.pid, 0)
        p.returncode = os.waitstatus_to_exitcode(status)
    with open(os.path.join(work, 'err.txt')) as f:
        text = f.read()
    return p.returncode, text, usage.ru_maxrss / 1024.0


def expect_refused(args, *fragments):
    code, err, _ = run(args)
    lines = err.strip().splitlines()
    if code != 1 or len(lines) != 1 or not all(f in err for f in fragments):
        failures.append('rtpbr-render %s: exit %d, stderr %r; expected exit 1 and one line with %s'
                        % (' '.join(args), code, err, fragments))


def png(rows_zlib, width=1, height=1):
    def chunk(kind, data):
        return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data))
    ihdr = struct.pack('>IIBBBBB', width, height, 8, 6, 0, 0, 0)  # RGBA8, not interlaced
    return b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', ihdr) + chunk(b'IDAT', rows_zlib) + chunk(b'IEND', b'')


def textured_scene(name, image):
    """quad_light with `image` as the floor's base colour."""
    folder = os.path.join(work, name)
    os.makedirs(folder)
    with open(os.path.join(scenes, 'quad_light.gltf')) as f:
        gltf = json.load(f)
    shutil.copy(os.path.join(scenes, 'quad_light.bin'), folder)
    with open(os.path.join(folder, 'tex.png'), 'wb') as f:
        f.write(image)
    gltf['images'] = [{'uri': 'tex.png'}]
    gltf['textures'] = [{'source': 0}]
    gltf['materials'][0]['pbrMetallicRoughness']['baseColorTexture'] = {'index': 0}
    path = os.path.join(folder, 'scene.gltf')
    with open(path, 'w') as f:
        json.dump(gltf, f)
    return path


quad = os.path.join(scenes, 'quad_light.gltf')
out_png = os.path.join(work, 'x.png')
# 16384 x 16384 x 16 samples at 64 + 64 bytes: refused however much memory the machine has.
expect_refused([quad, '-o', out_png, '--width', '16384', '--height', '16384', '--supersample', '4',
                '--memory-limit', '1024'],
               'rendering 16384x16384 with 4x4 supersampling needs 272.00 GiB of memory')
expect_refused([quad, '-o', out_png, '--width', '1024', '--height', '1024', '--memory-limit', '64'],
               'needs 128.0 MiB of memory', '--memory-limit')

# The hostile PNG: 5 bytes of rows, then 256 MiB of zeros, deflated piece by piece.
z = zlib.compressobj(9)
stream = z.compress(bytes([0, 10, 20, 30, 255]))
zeros = bytes(1 << 20)
for _ in range(256):
    stream += z.compress(zeros)
stream += z.flush()
bomb = textured_scene('bomb', png(stream))
valid = textured_scene('valid', png(zlib.compress(bytes([0, 10, 20, 30, 255]))))
size = ['-o', out_png, '--width', '64', '--height', '48']
code, err, peak_valid = run([valid] + size)
if code != 0:
    failures.append('the valid textured scene failed: %s' % err)
code, err, peak_bomb = run([bomb] + size)
print('peak RSS: %.1f MiB with the valid PNG, %.1f MiB with the one that inflates to 256 MiB'
      % (peak_valid, peak_bomb))
if code != 1 or 'expands past what its header declares' not in err:
    failures.append('the inflating PNG: exit %d, stderr %r' % (code, err))
if peak_bomb > peak_valid + 64:
    failures.append('the inflating PNG took %.1f MiB, the valid one %.1f' % (peak_bomb, peak_valid))

for f in failures:
    print('FAIL:', f)
sys.exit(1 if failures else 0)
