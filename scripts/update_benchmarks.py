#!/usr/bin/env python3
"""Replaces one measured section of docs/benchmarks.md by a freshly measured table.

    python3 scripts/update_benchmarks.py NAME BODY.md --command "bash scripts/x.sh" [--doc PATH]

The section is the text between the lines `<!-- NAME:begin -->` and `<!-- NAME:end -->`; it is
rewritten as a provenance line (date, machine, commit, command) followed by BODY.md. A section
that is not in the document yet is appended at its end under the heading `## NAME`. Run by the
scripts that measure (scripts/figures.sh, scripts/bench.sh, scripts/bench_remesh.sh,
examples/compare_freefem/run.sh), so that every table says how it was made.
"""
import argparse
import datetime
import os
import platform
import subprocess
import sys


def machine():
    model = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return f"{model}, {os.cpu_count()} cores"


def commit(root, doc):
    def git(*args):
        return subprocess.run(["git", "-C", root, *args], capture_output=True, text=True).stdout.strip()

    head = git("rev-parse", "--short=10", "HEAD") or "unknown"
    rel = os.path.relpath(doc, root)
    dirty = [l for l in git("status", "--porcelain", "--untracked-files=no").splitlines() if not l.endswith(rel)]
    return head + (" with local changes" if dirty else "")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("name")
    ap.add_argument("body")
    ap.add_argument("--command", required=True)
    ap.add_argument("--doc", default=None)
    a = ap.parse_args()
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    doc = a.doc or os.path.join(root, "docs", "benchmarks.md")
    body = open(a.body).read().strip("\n")
    date = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d")
    begin, end = f"<!-- {a.name}:begin -->", f"<!-- {a.name}:end -->"
    block = (f"{begin}\n*Measured {date} on {machine()}, commit {commit(root, doc)}; "
             f"command: `{a.command}`.*\n\n{body}\n{end}")
    text = open(doc).read() if os.path.exists(doc) else "# Benchmarks\n"
    if begin in text and end in text:
        i, j = text.index(begin), text.index(end) + len(end)
        text = text[:i] + block + text[j:]
    else:
        text = text.rstrip("\n") + f"\n\n## {a.name}\n\n{block}\n"
    tmp = doc + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, doc)
    print(f"{os.path.relpath(doc, root)}: section {a.name} updated", file=sys.stderr)


if __name__ == "__main__":
    main()
