#!/usr/bin/env python3
"""The include graph of rtpbr, checked (issue 16).

    python3 scripts/check_includes.py [--root DIR] [--quiet]

Reads every #include line of the C, C++, GLSL and HLSL files of the tree (the files git
tracks, or every file when DIR is not a git checkout), resolves each to a file of the tree,
prints the graph in words (component -> the components it includes, with the number of
include lines) and checks three rules:

  1. Layers. Nothing includes from a layer above its own:
       0  shaderlib/                          the shader library (pure math)
       1  scene/, common/                     the glTF loader; the shared runtime code of the
                                              programs (images, generators, colour maps, ...)
       2  engine/, oracle/, tools/            peers: the renderer, the path tracer, the tools
       3  samples/, bench/, tests/, fuzz/     programs on top of everything
  2. Peers. engine/, oracle/ and tools/ do not include each other, with one exception: the
     public header of librtpbr (engine/include/) is an API, so tools/ may include it (rtpbr-
     render is a client of the engine); engine/src/ is nobody's business but the engine's.
     On the ground floor scene/ and common/ do not include each other either (so common/
     may include shaderlib/ only; today it includes nothing of rtpbr).
     On the top layer tests/ may include samples/ and bench/ (it tests them), bench/ may
     include tests/common/ (the Vulkan host bootstrap of the tests, which the shader-
     statistics bench uses too); samples/ and fuzz/ include nothing of their layer.
  3. No circles: no file includes itself through a chain of includes (a depth-first search
     over the resolved file-to-file edges; every circle is printed once, as a path). And, as
     all the .c files of a folder usually share one internal header, the same search over
     their calls: no .c/.cpp file calls a function of another file of its folder that calls
     back into it through a chain of such calls (a helper file with the context in it, used
     by the files the context uses, is such a circle). A call edge is a word `name(` in one
     file where `name` is a function defined, not static, in exactly one other file of the
     same folder (a definition: a line at column 0 that names `name(` and opens a body).

Includes that resolve to no file of the tree (system and generated headers) are not edges;
folders named `fixtures` (the trees of this script's own test) are not read.
A quoted include is looked up next to the including file first; otherwise (and for <...>)
among the files whose path ends with the included path, the one nearest the including file.
Exit status: 0 when every rule holds, 1 otherwise (each breach is printed), 2 on bad usage.
"""
import argparse
import os
import re
import subprocess
import sys
from collections import defaultdict

SOURCE_EXTENSIONS = ('.c', '.h', '.cpp', '.hpp', '.cc', '.inl', '.glsl', '.frag', '.vert', '.comp', '.hlsl')
INCLUDE_RE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')

# (path prefix, component, layer), most specific prefix first.
COMPONENTS = [
    ('shaderlib/', 'shaderlib', 0),
    ('scene/', 'scene', 1),
    ('common/', 'common', 1),
    ('engine/include/', 'engine', 2),
    ('engine/', 'engine', 2),
    ('oracle/', 'oracle', 2),
    ('tools/', 'tools', 2),
    ('samples/', 'samples', 3),
    ('bench/', 'bench', 3),
    ('tests/', 'tests', 3),
    ('fuzz/', 'fuzz', 3),
]
LAYER_NAMES = {0: 'bottom', 1: 'ground floor', 2: 'peers', 3: 'top'}

# Includes across components of the same layer that the rules allow: (from, to, path prefix
# of the included file that makes it allowed).
ALLOWED_SIDEWAYS = [
    ('tools', 'engine', 'engine/include/'),
    ('tests', 'samples', 'samples/'),
    ('tests', 'bench', 'bench/'),
    ('bench', 'tests', 'tests/common/'),
]


def component_of(path):
    for prefix, name, layer in COMPONENTS:
        if path.startswith(prefix):
            return name, layer
    return None, None


def list_files(root):
    files = _list_files(root)
    # Test fixtures (trees of this script's own tests, which break the rules on purpose).
    return [f for f in files if 'fixtures' not in f.split('/')[:-1]]


def _list_files(root):
    try:
        out = subprocess.run(['git', '-C', root, 'ls-files', '-z', '--cached', '--others', '--exclude-standard'],
                             check=True, capture_output=True).stdout
        files = [f for f in out.decode().split('\0') if f]
        if files:
            return sorted(f for f in files if f.endswith(SOURCE_EXTENSIONS) and os.path.isfile(os.path.join(root, f)))
    except (OSError, subprocess.CalledProcessError):
        pass
    files = []
    for d, dirs, names in os.walk(root):
        dirs[:] = [x for x in dirs if not x.startswith('.') and x not in ('build', 'subprojects')]
        for n in names:
            if n.endswith(SOURCE_EXTENSIONS):
                files.append(os.path.relpath(os.path.join(d, n), root).replace(os.sep, '/'))
    return sorted(files)


def common_prefix_len(a, b):
    n = 0
    for x, y in zip(a.split('/'), b.split('/')):
        if x != y:
            break
        n += 1
    return n


class Resolver:
    def __init__(self, files):
        self.files = set(files)
        self.by_name = defaultdict(list)
        for f in files:
            self.by_name[f.rsplit('/', 1)[-1]].append(f)

    def resolve(self, includer, kind, target):
        target = target.strip()
        if kind == '"':
            here = os.path.dirname(includer)
            local = os.path.normpath(os.path.join(here, target)).replace(os.sep, '/')
            if local in self.files:
                return local
        norm = os.path.normpath(target).replace(os.sep, '/')
        if norm.startswith('../') or (kind == '<' and '/' not in norm):
            return None  # outside the tree, or a system header such as <math.h>
        candidates = [f for f in self.by_name.get(norm.rsplit('/', 1)[-1], [])
                      if (f == norm or f.endswith('/' + norm)) and f != includer]
        if not candidates:
            return None
        # The nearest to the including file; ties go to the shortest path, then by name.
        return max(candidates, key=lambda f: (common_prefix_len(f, includer), -len(f), f))


def read_includes(root, path):
    out = []
    try:
        with open(os.path.join(root, path), encoding='utf-8', errors='replace') as fh:
            for number, line in enumerate(fh, 1):
                m = INCLUDE_RE.match(line)
                if m:
                    out.append((number, m.group(1), m.group(2)))
    except OSError:
        pass
    return out


DEFINITION_RE = re.compile(r'^(?!static\b|typedef\b|return\b|else\b|if\b|for\b|while\b|switch\b|do\b|#)'
                           r'[A-Za-z_][\w\s\*&:<>,]*?\b([A-Za-z_]\w*)\s*\(')
CALL_RE = re.compile(r'\b([A-Za-z_]\w*)\s*\(')
COMMENT_RE = re.compile(r'//[^\n]*|/\*.*?\*/', re.S)
STRING_RE = re.compile(r'"(?:\\.|[^"\\\n])*"')


def defined_functions(text):
    """Names of the functions a C/C++ file defines with external linkage (column-0 style)."""
    names = set()
    lines = text.split('\n')
    anonymous = 0
    for i, line in enumerate(lines):
        if line.startswith('namespace {'):
            anonymous += 1
        elif line.startswith('} // namespace') and anonymous and 'namespace {' not in line:
            anonymous = 0 if 'anonymous' in line or line.strip() == '} // namespace' else anonymous
        if anonymous:
            continue
        m = DEFINITION_RE.match(line)
        if not m or line.rstrip().endswith(';'):
            continue
        # the body opens on this line or on the first line after the parameter list
        rest = '\n'.join(lines[i:i + 8])
        close = rest.find(')')
        after = rest[close + 1:].lstrip() if close >= 0 else ''
        if after.startswith('{') or re.match(r'(const\s*)?(noexcept\s*)?\{', after):
            names.add(m.group(1))
    names.discard('main')
    return names


def call_edges(root, files):
    """file -> files of the same folder whose functions it calls (see rule 3)."""
    by_dir = defaultdict(list)
    for f in files:
        if f.endswith(('.c', '.cpp', '.cc')):
            by_dir[os.path.dirname(f)].append(f)
    edges = defaultdict(set)
    for d, members in by_dir.items():
        if len(members) < 2:
            continue
        texts, owners = {}, defaultdict(set)
        for f in members:
            try:
                with open(os.path.join(root, f), encoding='utf-8', errors='replace') as fh:
                    texts[f] = STRING_RE.sub('""', COMMENT_RE.sub(' ', fh.read()))
            except OSError:
                continue
            for name in defined_functions(texts[f]):
                owners[name].add(f)
        unique = {name: next(iter(fs)) for name, fs in owners.items() if len(fs) == 1}
        for f, text in texts.items():
            for name in set(CALL_RE.findall(text)):
                owner = unique.get(name)
                if owner and owner != f:
                    edges[f].add(owner)
    return edges


def find_cycles(edges):
    """Every elementary circle found by a depth-first search, each reported once (as the
    path from its smallest file), in a deterministic order."""
    cycles, seen = [], set()
    state = {}  # 1 = on the stack, 2 = done
    stack = []

    def visit(node):
        state[node] = 1
        stack.append(node)
        for nxt in sorted(edges.get(node, ())):
            if state.get(nxt) == 1:
                loop = stack[stack.index(nxt):]
                start = loop.index(min(loop))
                loop = loop[start:] + loop[:start]
                key = tuple(loop)
                if key not in seen:
                    seen.add(key)
                    cycles.append(loop)
            elif nxt not in state:
                visit(nxt)
        stack.pop()
        state[node] = 2

    sys.setrecursionlimit(max(10000, sys.getrecursionlimit()))
    for node in sorted(edges):
        if node not in state:
            visit(node)
    return cycles


def check(root, quiet=False, out=sys.stdout):
    files = list_files(root)
    resolver = Resolver(files)
    edges = defaultdict(set)
    comp_edges = defaultdict(lambda: defaultdict(int))
    breaches = []
    for f in files:
        fc, fl = component_of(f)
        if fc is None:
            continue
        for number, kind, target in read_includes(root, f):
            to = resolver.resolve(f, kind, target)
            if to is None:
                continue
            edges[f].add(to)
            tc, tl = component_of(to)
            if tc is None:
                continue
            if tc != fc:
                comp_edges[fc][tc] += 1
            where = '%s:%d: #include %s%s%s -> %s' % (f, number, kind, target, '"' if kind == '"' else '>', to)
            if tl > fl:
                breaches.append('upward include (%s, layer %d, includes %s, layer %d): %s' % (fc, fl, tc, tl, where))
            elif tl == fl and tc != fc:
                if not any(a == fc and b == tc and to.startswith(p) for a, b, p in ALLOWED_SIDEWAYS):
                    breaches.append('include between peers (%s includes %s): %s' % (fc, tc, where))
    cycles = find_cycles(edges)
    for loop in cycles:
        breaches.append('files include each other in a circle: ' + ' -> '.join(loop + [loop[0]]))
    calls = call_edges(root, files)
    call_cycles = find_cycles(calls)
    for loop in call_cycles:
        breaches.append('files call each other in a circle: ' + ' -> '.join(loop + [loop[0]]))

    if not quiet:
        print('Include graph of %s (%d files, %d resolved include edges):' %
              (os.path.abspath(root), len(files), sum(len(v) for v in edges.values())), file=out)
        seen_components = []
        for _, name, layer in COMPONENTS:
            if name not in [c for c, _ in seen_components]:
                seen_components.append((name, layer))
        for name, layer in seen_components:
            if not any(component_of(f)[0] == name for f in files):
                continue
            targets = comp_edges.get(name, {})
            said = ', '.join('%s (%d)' % (t, n) for t, n in sorted(targets.items(), key=lambda kv: (component_of_name_layer(kv[0]), kv[0])))
            print('  %-13s [layer %d, %s] -> %s' % (name, layer, LAYER_NAMES[layer], said or 'nothing of the tree'),
                  file=out)
        print('File-level circles: %d of includes, %d of calls (over %d call edges between files of one folder).' %
              (len(cycles), len(call_cycles), sum(len(v) for v in calls.values())), file=out)
    for b in breaches:
        print('BREACH: ' + b, file=out)
    if not breaches and not quiet:
        print('OK: nothing includes from a layer above, peers include only what the rules allow, no circles.',
              file=out)
    return 1 if breaches else 0


def component_of_name_layer(name):
    for _, n, layer in COMPONENTS:
        if n == name:
            return layer
    return 99


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--root', default=os.path.join(os.path.dirname(os.path.abspath(__file__)), '..'),
                    help='the tree to read (default: this checkout)')
    ap.add_argument('--quiet', action='store_true', help='print only the breaches')
    args = ap.parse_args()
    if not os.path.isdir(args.root):
        print('check_includes: %s is not a directory' % args.root, file=sys.stderr)
        return 2
    return check(args.root, args.quiet)


if __name__ == '__main__':
    sys.exit(main())
