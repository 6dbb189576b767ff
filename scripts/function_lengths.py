#!/usr/bin/env python3
"""Lists the functions of mesher/, adapt/ and fem/ longer than a limit; exits 1 if there is one.

    python3 scripts/function_lengths.py [--limit 100] [--top 10] [DIR ...]

The sources are clang-formatted (.clang-format: namespaces not indented), so a function defined
at namespace scope starts with a signature at column 0 and ends at the first later line that is
exactly "}". Its length is the number of lines from the signature's first line to that brace.
Member functions defined inside a class body are indented and skipped: they are one-liners here.
"""
import argparse
import pathlib
import re
import sys

NOT_FUNCTION = re.compile(r"^(namespace|struct|class|enum|union|extern|template\s*<[^>]*>\s*(struct|class))\b")


def functions(path):
    lines = path.read_text(encoding="utf-8").splitlines()
    i = 0
    while i < len(lines):
        line = lines[i]
        if line and not line[0].isspace() and not line.startswith(("//", "#", "}")) and not NOT_FUNCTION.match(line):
            # The signature may span lines; it ends at the line whose last character opens the body.
            j = i
            while j < len(lines) and not lines[j].rstrip().endswith(("{", ";")) and j - i < 12:
                j += 1
            if j < len(lines) and lines[j].rstrip().endswith("{") and "(" in " ".join(lines[i:j + 1]) \
                    and "=" not in lines[i].split("(")[0]:
                k = j + 1
                while k < len(lines) and lines[k] != "}":
                    k += 1
                name = lines[i].split("(")[0].split()[-1] if lines[i].split("(")[0].split() else lines[i]
                yield name, i + 1, k - i + 1
                i = k
        i += 1


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dirs", nargs="*", default=["mesher", "adapt", "fem"])
    ap.add_argument("--limit", type=int, default=100)
    ap.add_argument("--top", type=int, default=0, help="also print the N longest functions")
    args = ap.parse_args()
    root = pathlib.Path(__file__).resolve().parents[1]
    found = []
    for d in args.dirs:
        for p in sorted((root / d).rglob("*.[ch]pp")):
            found += [(n, p.relative_to(root), line, length) for n, line, length in functions(p)]
    found.sort(key=lambda f: -f[3])
    for n, p, line, length in found[:args.top]:
        print(f"{length:4d}  {p}:{line}  {n}")
    long = [f for f in found if f[3] > args.limit]
    for n, p, line, length in long:
        print(f"{p}:{line}: {n} is {length} lines (limit {args.limit})", file=sys.stderr)
    print(f"{len(found)} functions, {len(long)} over {args.limit} lines")
    return 1 if long else 0


if __name__ == "__main__":
    sys.exit(main())
