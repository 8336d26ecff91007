#!/usr/bin/env python3
"""Self-test of scripts/check_includes.py on two small trees: includes-good must pass;
includes-bad (two upward includes, one of them from the ground floor common/, an include
between peers, two headers that include each other, two .c files that call each other) must
fail with exactly those five breaches."""
import io
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, '..', '..', 'scripts'))
import check_includes  # noqa: E402

failures = []


def run(tree):
    out = io.StringIO()
    rc = check_includes.check(os.path.join(here, 'fixtures', tree), out=out)
    return rc, out.getvalue()


rc, text = run('includes-good')
if rc != 0 or 'BREACH' in text:
    failures.append('includes-good: expected a pass, got exit %d:\n%s' % (rc, text))
for edge in ('scene         [layer 1, ground floor] -> shaderlib (1)', 'tools         [layer 2, peers] -> engine (1)',
             'oracle        [layer 2, peers] -> common (1)', 'common        [layer 1, ground floor] -> nothing of the tree'):
    if edge not in text:
        failures.append('includes-good: the graph lacks "%s":\n%s' % (edge, text))

rc, text = run('includes-bad')
breaches = sorted(line for line in text.splitlines() if line.startswith('BREACH'))
expected = sorted([
    'BREACH: upward include (shaderlib, layer 0, includes engine, layer 2): shaderlib/rtpbr/math.h:2: '
    '#include "rtpbr/rtpbr.h" -> engine/include/rtpbr/rtpbr.h',
    'BREACH: upward include (common, layer 1, includes tools, layer 2): common/image_read.cpp:2: '
    '#include "flip.h" -> tools/imgdiff/flip.h',
    'BREACH: include between peers (oracle includes engine): oracle/render.cpp:2: '
    '#include "../engine/src/first.h" -> engine/src/first.h',
    'BREACH: files include each other in a circle: engine/src/first.h -> engine/src/second.h -> engine/src/first.h',
    'BREACH: files call each other in a circle: engine/src/context.c -> engine/src/device.c -> engine/src/context.c',
])
if rc != 1:
    failures.append('includes-bad: expected exit 1, got %d' % rc)
if breaches != expected:
    failures.append('includes-bad: breaches differ.\nexpected:\n  %s\ngot:\n  %s' %
                    ('\n  '.join(expected), '\n  '.join(breaches)))

for f in failures:
    print('FAIL: ' + f)
print('%d failure(s)' % len(failures))
sys.exit(1 if failures else 0)
