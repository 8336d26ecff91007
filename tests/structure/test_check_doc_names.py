#!/usr/bin/env python3
"""Self-test of scripts/check_doc_names.py on a small tree (fixtures/docs) whose docs quote
names that exist and stale ones: exactly the stale ones must be reported, each once."""
import io
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, '..', '..', 'scripts'))
import check_doc_names  # noqa: E402

out = io.StringIO()
rc = check_doc_names.check(os.path.join(here, 'fixtures', 'docs'), out=out)
text = out.getvalue()
got = sorted(line.split(' is not in the tree')[0] for line in text.splitlines() if line.startswith('MISSING'))
expected = sorted([
    'MISSING: README.md:6: identifier `rtpbr_gone_function`',
    'MISSING: README.md:6: identifier `RTPBR_GONE_LIMIT`',
    'MISSING: README.md:6: path `src/gone.c`',
    'MISSING: README.md:6: program `rtpbr-gone`',
    'MISSING: README.md:6: flag `--gone-flag`',
    'MISSING: docs/notes.md:1: identifier `D_Gone`',
])
failures = []
if rc != 1:
    failures.append('expected exit 1, got %d' % rc)
if got != expected:
    failures.append('reported names differ.\nexpected:\n  %s\ngot:\n  %s\nfull output:\n%s' %
                    ('\n  '.join(expected), '\n  '.join(got), text))
for f in failures:
    print('FAIL: ' + f)
print('%d failure(s)' % len(failures))
sys.exit(1 if failures else 0)
