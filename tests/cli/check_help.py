#!/usr/bin/env python3
"""`--help` of one program (issue 31): lists every option the program parses, and every key.

usage: check_help.py [--interpreter PY] [--keys SOURCE:FUNCTION] PROGRAM SOURCE...

Runs PROGRAM -h and PROGRAM --help (with PY in front for a script) and fails unless both exit
0 with the same non-empty text on stdout and nothing on stderr; runs it with an unknown
option and fails unless it exits 2 with nothing on stdout and, on stderr, a usage (or a
message that points at --help). Then reads
the option strings the program compares its arguments with from each SOURCE (C/C++:
strcmp(arg, "--foo") and arg == "--foo"; Python: the names given to add_argument and the
strings compared on a line that reads sys.argv; shell: getopts letters and case patterns) and fails for each one the help text does not name. With
--keys, every GLFW_KEY_* that FUNCTION of SOURCE handles must be named in the key column of
the help (a line "  KEYS  what they do"), in the spelling of KEY_NAMES.
"""
import os
import re
import subprocess
import sys

OPTION = r"-{1,2}[A-Za-z][A-Za-z0-9-]*"
C_COMPARISONS = [
    re.compile(r"strn?cmp\s*\([^,;]*,\s*\"(" + OPTION + r")\""),  # strcmp(arg, "--foo")
    re.compile(r"[=!]=\s*\"(" + OPTION + r")\""),  # arg == "--foo"
    re.compile(r"\"(" + OPTION + r")\"\s*[=!]="),  # "--foo" == arg
]
PY_ADD_ARGUMENT = re.compile(r"add_argument\(\s*((?:[\"']" + OPTION + r"[\"']\s*,?\s*)+)")
PY_ARGV_TEST = re.compile(r"(?:==|\bin)\s*\(?\s*((?:[\"']" + OPTION + r"[\"']\s*,?\s*)+)")
PY_STRING = re.compile(r"[\"'](" + OPTION + r")[\"']")
SH_GETOPTS = re.compile(r"getopts\s+[\"']([^\"']+)[\"']")
SH_CASE = re.compile(r"^\s*(" + OPTION + r"(?:\s*\|\s*" + OPTION + r")*)\s*\)", re.M)  # -h | --help)
SH_TEST = re.compile(r"=\s*(" + OPTION + r")\s*\]")  # [ "$1" = --help ]

# How the help names a GLFW key: letters and digits as themselves, the others spelled here.
# A key missing from this table fails the test, so that a new kind of key gets a name.
KEY_NAMES = {
    "ESCAPE": "Esc", "HOME": "Home", "TAB": "Tab", "LEFT": "Left", "RIGHT": "Right", "UP": "Up",
    "DOWN": "Down", "PAGE_UP": "PgUp", "PAGE_DOWN": "PgDn", "LEFT_BRACKET": "[",
    "RIGHT_BRACKET": "]", "EQUAL": "=", "MINUS": "-", "SPACE": "Space", "ENTER": "Enter",
}


def parsed_options(path):
    text = open(path, encoding="utf-8").read()
    found = set()
    if path.endswith(".sh"):
        for m in SH_GETOPTS.finditer(text):
            found.update("-" + c for c in m.group(1) if c.isalpha())
        for m in SH_CASE.finditer(text):
            found.update(o.strip() for o in m.group(1).split("|"))
        found.update(SH_TEST.findall(text))
    elif path.endswith(".py"):
        for m in PY_ADD_ARGUMENT.finditer(text):
            found.update(PY_STRING.findall(m.group(1)))
        for line in text.splitlines():
            if "argv" in line:
                for m in PY_ARGV_TEST.finditer(line):
                    found.update(PY_STRING.findall(m.group(1)))
    else:
        for pattern in C_COMPARISONS:
            found.update(pattern.findall(text))
    return found


def handled_keys(path, function):
    text = open(path, encoding="utf-8").read()
    m = re.search(r"^[^\n]*\b" + re.escape(function) + r"\([^)]*\)\s*\{\n(.*?)^\}", text, re.S | re.M)
    if not m:
        sys.exit(f"check_help: no function {function} in {path}")
    return set(re.findall(r"GLFW_KEY_(\w+)", m.group(1)))


def key_column(help_text):
    """The tokens of the first column of lines '  KEYS  what they do'."""
    tokens = set()
    for line in help_text.splitlines():
        m = re.match(r"^ {2}(\S.*?) {2,}\S", line)
        if m:
            tokens.update(t for t in re.split(r"[\s/,]+", m.group(1)) if t)
    return tokens


def named(option, text):
    return re.search(r"(?<![A-Za-z0-9-])" + re.escape(option) + r"(?![A-Za-z0-9-])", text) is not None


def run(command):
    env = dict(os.environ, DISPLAY="", WAYLAND_DISPLAY="")  # help comes before any window
    return subprocess.run(command, capture_output=True, text=True, timeout=120, env=env,
                          stdin=subprocess.DEVNULL)


def main(argv):
    interpreter, keys = [], None
    while argv and argv[0] in ("--interpreter", "--keys"):
        if argv[0] == "--interpreter":
            interpreter = [argv[1]]
        else:
            keys = argv[1]
        argv = argv[2:]
    if len(argv) < 2:
        sys.exit(__doc__)
    program, sources = argv[0], argv[1:]
    name = os.path.basename(program)
    failures = []

    helps = {}
    for flag in ("-h", "--help"):
        p = run(interpreter + [program, flag])
        helps[flag] = p.stdout
        if p.returncode != 0 or not p.stdout.strip() or p.stderr.strip():
            failures.append(f"{name} {flag}: exit {p.returncode}, {len(p.stdout)} characters on stdout, "
                            f"stderr {p.stderr.strip()[:300]!r} (want 0, the help, nothing)")
    if helps["-h"] != helps["--help"]:
        failures.append(f"{name}: -h and --help print different texts")
    text = helps["--help"]

    p = run(interpreter + [program, "--no-such-option-31"])
    if p.returncode != 2 or p.stdout.strip() or not ("usage" in p.stderr.lower() or "--help" in p.stderr):
        failures.append(f"{name} --no-such-option-31: exit {p.returncode}, stdout {p.stdout.strip()[:200]!r}, "
                        f"stderr {p.stderr.strip()[:200]!r} (want 2, nothing, a usage or where it is)")

    options = set()
    for source in sources:
        options |= parsed_options(source)
    if not options:
        failures.append(f"{name}: found no option comparisons in {', '.join(sources)} (the check reads none)")
    for option in sorted(options - {"-h", "--help"}):  # those two answered above
        if not named(option, text):
            failures.append(f"{name}: parses {option} but --help does not name it")

    if keys:
        source, function = keys.rsplit(":", 1)
        column = key_column(text)
        glfw = handled_keys(source, function)
        if not glfw:
            failures.append(f"{name}: no GLFW_KEY_* in {function} of {source}")
        for key in sorted(glfw):
            spelled = KEY_NAMES.get(key, key if re.fullmatch(r"[A-Z0-9]", key) else None)
            if spelled is None:
                failures.append(f"{name}: GLFW_KEY_{key} has no name in check_help.py's KEY_NAMES")
            elif spelled not in column:
                failures.append(f"{name}: handles GLFW_KEY_{key} but --help lists no key '{spelled}'")
        print(f"{name}: {len(glfw)} keys checked")

    print(f"{name}: {len(options)} options checked: {' '.join(sorted(options))}")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
