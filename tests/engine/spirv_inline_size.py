#!/usr/bin/env python3
"""Test (suite engine): no engine pipeline makes the driver inline more than LIMIT SPIR-V
instructions. The size a driver's first passes see is the entry point's code with every call
replaced by its callee's, recursively (Mesa's NIR inlines every call before it folds constant
arguments), and their cost grows faster than that size (docs/performance.md, "Pipeline compile
time"). The measure is read from the SPIR-V glslang wrote, so it is exact and the same on every
machine, unlike a compile time.

    spirv_inline_size.py [--limit N] RTPBR_SPIRV_HEADER.h...

Each argument is one of the engine's generated headers (glslang --vn: a uint32_t array). Prints
each pipeline's inlined and written instruction counts; exits 1 when one exceeds the limit.
Measured 2026-12-06: before area_light_part.inl the tube classes inlined 219,773 (basic),
349,633 (full) and 683,621 (full, _cpu) instructions, the forward sphere variant 412,740
(GGX, Kulla-Conty), and RADV took 13 to 48 s over the tube classes; after, the largest is
131,122 (the full tube class's _cpu build, Beckmann), and RADV takes 2.7 to 5.6 s.
"""
import re
import sys

LIMIT = 200000

OP_ENTRY_POINT, OP_FUNCTION, OP_FUNCTION_END, OP_FUNCTION_CALL = 15, 54, 56, 57


def inlined_size(words):
    """(inlined, written): the entry point's instruction count with every call replaced by
    its callee's, recursively, and the module's functions' own count."""
    if len(words) < 5 or words[0] != 0x07230203:
        raise ValueError("not SPIR-V (magic %#x)" % (words[0] if words else 0))
    funcs, cur, entry, i = {}, None, None, 5
    while i < len(words):
        op, n = words[i] & 0xFFFF, words[i] >> 16
        if n == 0 or i + n > len(words):
            raise ValueError("malformed instruction at word %d" % i)
        if op == OP_ENTRY_POINT and entry is None:
            entry = words[i + 2]
        elif op == OP_FUNCTION:
            cur = words[i + 2]
            funcs[cur] = [0, []]
        if cur is not None:
            funcs[cur][0] += 1
            if op == OP_FUNCTION_CALL:
                funcs[cur][1].append(words[i + 3])
        if op == OP_FUNCTION_END:
            cur = None
        i += n
    if entry is None or entry not in funcs:
        raise ValueError("no entry point")
    memo = {}

    def size(f, depth=0):
        if depth > 64:
            raise ValueError("call depth over 64 (recursion?)")
        if f not in memo:
            own, calls = funcs[f]
            memo[f] = own + sum(size(c, depth + 1) for c in calls)
        return memo[f]

    return size(entry), sum(v[0] for v in funcs.values())


def self_test():
    # main calls f twice, f calls g once: main 4 + 2 x (f 4 + g 3) = 18; written 4 + 4 + 3.
    def ins(op, *ops):
        return [((1 + len(ops)) << 16) | op] + list(ops)
    w = [0x07230203, 0x00010500, 0, 100, 0]
    w += ins(OP_ENTRY_POINT, 5, 1)
    w += ins(OP_FUNCTION, 2, 3, 0, 4) + ins(248, 9) + ins(253) + ins(OP_FUNCTION_END)  # g: 3 + end
    w += ins(OP_FUNCTION, 2, 6, 0, 4) + ins(OP_FUNCTION_CALL, 2, 7, 3) + ins(253) + ins(OP_FUNCTION_END)
    w += ins(OP_FUNCTION, 2, 1, 0, 4) + ins(OP_FUNCTION_CALL, 2, 8, 6) + ins(OP_FUNCTION_CALL, 2, 9, 6) + \
        ins(OP_FUNCTION_END)
    got = inlined_size(w)
    if got != (4 + 2 * (4 + 4), 12):
        raise AssertionError("self-test: inlined_size gave %s" % (got,))


def main(argv):
    limit, paths = LIMIT, argv[1:]
    if len(paths) > 1 and paths[0] == "--limit":
        limit, paths = int(paths[1]), paths[2:]
    if not paths:
        print("usage: spirv_inline_size.py [--limit N] RTPBR_SPIRV_HEADER.h...", file=sys.stderr)
        return 2
    self_test()
    failed = []
    rows = []
    for path in paths:
        text = open(path).read()
        words = [int(x, 16) for x in re.findall(r"0x[0-9a-fA-F]{8}", text)]
        name = re.search(r"rtpbr_spirv_(\w+)\.h$", path)
        name = name.group(1) if name else path
        inlined, written = inlined_size(words)
        rows.append((inlined, written, name))
        if inlined > limit:
            failed.append(name)
    for inlined, written, name in sorted(rows, reverse=True):
        print("%-48s inlined %8d  written %7d%s" % (name, inlined, written, "  OVER" if name in failed else ""))
    if failed:
        print("spirv_inline_size: %d pipeline(s) inline more than %d SPIR-V instructions: %s "
              "(docs/performance.md, \"Pipeline compile time\")" % (len(failed), limit, ", ".join(failed)))
        return 1
    print("spirv_inline_size: %d pipelines, the largest %d inlined instructions (limit %d)" %
          (len(rows), max(r[0] for r in rows), limit))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
