#!/usr/bin/env python3
"""Every name the docs quote in backticks exists in the tree (issue 16).

    python3 scripts/check_doc_names.py [--root DIR] [--list]

Reads the inline code spans (`...`, outside fenced blocks) of README.md, every README.md
below it, docs/*.md and shaderlib/luts/*.md (CHANGELOG.md is history and is not read) and
checks, in each span:

  - C and shader identifiers of the project: words starting rtpbr_, RTPBR_, LTC_, KC_, or a
    shader-term prefix (D_, G_, V_, F_, Fd_, BRDF_, Sample_, PDF_, Lambda_), and any word
    written as a call, `name(` -- each must be a word of a source or build file of the tree;
  - program names rtpbr-NAME and command-line flags --NAME -- each must appear in a source,
    build or script file;
  - paths: a span holding a '/' that starts with a top-level folder of the tree, or a file
    name with a source extension (.h .c .cpp .hpp .glsl .comp .frag .vert .hlsl .py .sh
    .build .json) -- each must be a file or folder of the tree (a bare file name may sit in
    any folder; a glob such as `*.exr` or `tools/*` is a pattern, not a name, and is
    skipped).

Names that are not the tree's (other projects' APIs, meson's flags) are listed, with the
reason, in scripts/doc_names_allow.txt (one `name  # why` a line). Exit status 0 when every
name is found, 1 otherwise (each missing name is printed with its file and line), 2 on bad
usage. --list prints every name checked.
"""
import argparse
import os
import re
import subprocess
import sys

DOC_GLOBS_TOP = ['README.md']
SOURCE_EXTENSIONS = ('.c', '.h', '.cpp', '.hpp', '.cc', '.inl', '.glsl', '.frag', '.vert', '.comp', '.hlsl',
                     '.py', '.sh', '.build', '.txt', '.in', '.json', '.cmake', '.js', '.options', '.supp')
SOURCE_NAMES = ('meson.build', 'meson_options.txt', 'run', 'Makefile', 'CMakeLists.txt')
PATH_EXTENSIONS = ('.h', '.c', '.cpp', '.hpp', '.glsl', '.comp', '.frag', '.vert', '.hlsl', '.py', '.sh',
                   '.build', '.json')
IDENT_PREFIX_RE = re.compile(r'\b((?:rtpbr_|RTPBR_|LTC_|KC_|D_|G_|V_|F_|Fd_|BRDF_|Sample_|PDF_|Lambda_)\w*)')
CALL_RE = re.compile(r'\b([A-Za-z_]\w*)\s*\(')
PROGRAM_RE = re.compile(r'(?<![\w/.-])(rtpbr-[a-z0-9-]+)')
FLAG_RE = re.compile(r'(?<![\w-])(--[a-z][a-z0-9-]*)')
SPAN_RE = re.compile(r'(`+)(.+?)\1')
WORD_RE = re.compile(r'[A-Za-z_]\w*')
TEXT_TOKEN_RE = re.compile(r'--?[a-z][a-z0-9-]*|[A-Za-z_][\w-]*')
PATH_TOKEN_RE = re.compile(r'[\w.-]+\.\w+')


def tracked_files(root):
    try:
        out = subprocess.run(['git', '-C', root, 'ls-files', '-z', '--cached', '--others', '--exclude-standard'],
                             check=True, capture_output=True).stdout
        files = [f for f in out.decode().split('\0') if f and os.path.exists(os.path.join(root, f))]
        if files:
            return sorted(files)
    except (OSError, subprocess.CalledProcessError):
        pass
    files = []
    for d, dirs, names in os.walk(root):
        dirs[:] = [x for x in dirs if not x.startswith('.') and x not in ('build', 'subprojects', 'node_modules')]
        files += [os.path.relpath(os.path.join(d, n), root).replace(os.sep, '/') for n in names]
    return sorted(files)


def doc_files(files):
    docs = []
    for f in files:
        parts = f.split('/')
        if 'fixtures' in parts[:-1]:
            continue  # the trees of this script's own test
        if parts[-1] == 'README.md' or (len(parts) == 2 and parts[0] == 'docs' and f.endswith('.md')) or \
                (f.startswith('shaderlib/luts/') and f.endswith('.md') and f.count('/') == 2):
            docs.append(f)
    return docs


def is_source(f):
    name = f.rsplit('/', 1)[-1]
    return name.endswith(SOURCE_EXTENSIONS) or name in SOURCE_NAMES


def load_allowlist(path):
    allowed = set()
    if os.path.exists(path):
        with open(path, encoding='utf-8') as fh:
            for line in fh:
                name = line.split('#', 1)[0].strip()
                if name:
                    allowed.add(name)
    return allowed


def code_spans(text):
    """(line number, span text) of the inline code spans outside fenced blocks."""
    fenced = False
    for number, line in enumerate(text.split('\n'), 1):
        if line.lstrip().startswith(('```', '~~~')):
            fenced = not fenced
            continue
        if fenced:
            continue
        for m in SPAN_RE.finditer(line):
            yield number, m.group(2).strip()


def names_in_span(span, top_dirs):
    """(kind, name) pairs the span quotes."""
    out = []
    for m in IDENT_PREFIX_RE.finditer(span):
        out.append(('identifier', m.group(1)))
    for m in CALL_RE.finditer(span):
        if not span[:m.start()].rstrip().endswith(('-', '/')):
            out.append(('identifier', m.group(1)))
    for m in PROGRAM_RE.finditer(span):
        out.append(('program', m.group(1).rstrip('-')))
    for m in FLAG_RE.finditer(span):
        out.append(('flag', m.group(1)))
    token = span.split()[0] if span.split() else ''
    token = token.rstrip('.,;:)')
    if '*' not in token and '{' not in token and '<' not in token and not token.startswith(('http', '-')):
        first = token.split('/', 1)[0]
        if ('/' in token and first in top_dirs) or (token.endswith(PATH_EXTENSIONS) and '/' not in token and
                                                   re.fullmatch(r'[\w.-]+', token)):
            out.append(('path', token.split(':', 1)[0]))
    return list(dict.fromkeys(out))  # each name once per span, in order


def check(root, list_all=False, out=sys.stdout, allow_path=None):
    files = tracked_files(root)
    file_set = set(files)
    dir_set = {f.rsplit('/', i)[0] for f in files for i in range(1, f.count('/') + 1)}
    basenames = {f.rsplit('/', 1)[-1] for f in files}
    top_dirs = {f.split('/', 1)[0] for f in files if '/' in f}
    words, text_tokens, file_names = set(), set(), set()
    docs = doc_files(files)
    for f in files:
        if not is_source(f) or f in docs:
            continue
        try:
            with open(os.path.join(root, f), encoding='utf-8', errors='replace') as fh:
                text = fh.read()
        except OSError:
            continue
        words.update(WORD_RE.findall(text))
        text_tokens.update(TEXT_TOKEN_RE.findall(text))
        file_names.update(PATH_TOKEN_RE.findall(text))
    allowed = load_allowlist(allow_path or os.path.join(root, 'scripts', 'doc_names_allow.txt'))
    missing, checked = [], 0
    for doc in docs:
        with open(os.path.join(root, doc), encoding='utf-8', errors='replace') as fh:
            text = fh.read()
        for number, span in code_spans(text):
            for kind, name in names_in_span(span, top_dirs):
                checked += 1
                if kind == 'identifier':
                    found = name in words
                elif kind in ('program', 'flag'):
                    found = name in text_tokens
                else:
                    rel = os.path.normpath(os.path.join(os.path.dirname(doc), name)).replace(os.sep, '/')
                    found = any(p.rstrip('/') in file_set or p.rstrip('/') in dir_set for p in (name, rel)) or \
                        ('/' not in name and (name in basenames or name in file_names))
                if list_all:
                    print('%s:%d: %s %s: %s' % (doc, number, kind, name, 'found' if found else 'MISSING'), file=out)
                if not found and name not in allowed:
                    missing.append('%s:%d: %s `%s` is not in the tree (in `%s`)' % (doc, number, kind, name, span))
    for m in missing:
        print('MISSING: ' + m, file=out)
    print('%d names checked in %d documents, %d missing.' % (checked, len(docs), len(missing)), file=out)
    return 1 if missing else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--root', default=os.path.join(os.path.dirname(os.path.abspath(__file__)), '..'))
    ap.add_argument('--list', action='store_true', help='print every name checked')
    args = ap.parse_args()
    if not os.path.isdir(args.root):
        print('check_doc_names: %s is not a directory' % args.root, file=sys.stderr)
        return 2
    return check(args.root, args.list)


if __name__ == '__main__':
    sys.exit(main())
