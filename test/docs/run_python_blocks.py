#!/usr/bin/env python3
"""Runs every fenced ```python block of the given Markdown files, in order, one namespace per file
(a later block may use the names an earlier one defined, as a reader would), and fails with the
file and line of the first block that raises.

    run_python_blocks.py [--skip-module NAME]... FILE.md...

--skip-module NAME: a block that imports NAME is reported as skipped instead of run (for an
optional package that could not be installed; the caller says why)."""

import argparse
import re
import sys
import time

BLOCK = re.compile(r"^```python\n(.*?)^```", re.S | re.M)


def blocks(path):
    text = open(path, encoding="utf-8").read()
    for match in BLOCK.finditer(text):
        yield text.count("\n", 0, match.start()) + 2, match.group(1)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--skip-module", action="append", default=[])
    parser.add_argument("files", nargs="+")
    args = parser.parse_args()
    count = 0
    for path in args.files:
        namespace = {"__name__": "__main__"}
        for line, code in blocks(path):
            where = "%s:%d" % (path, line)
            skipped = [m for m in args.skip_module
                       if re.search(r"^\s*(import|from)\s+%s\b" % re.escape(m), code, re.M)]
            if skipped:
                print("skipped %s (imports %s)" % (where, ", ".join(skipped)))
                continue
            start = time.time()
            try:
                exec(compile(code, where, "exec"), namespace)
            except BaseException:
                print("FAILED: the Python block at %s" % where, file=sys.stderr)
                raise
            print("ok %s (%.1f s)" % (where, time.time() - start))
            count += 1
    if count == 0:
        sys.exit("no Python block ran in %s" % " ".join(args.files))


if __name__ == "__main__":
    main()
