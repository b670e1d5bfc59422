#!/usr/bin/env python3
"""Test driver for the mpm3d-compare tests: run a command and check its exit status, what
it prints and the files it writes (ctest's PASS_REGULAR_EXPRESSION ignores the exit status).

  expect.py --rc N [--stdout RE]... [--not-stdout RE]... [--stderr RE]... [--file PATH]...
            [--clean DIR]... [--needs MODULE] -- COMMAND...

--clean removes DIR before the run; --needs skips the test (exit 77) when this python3
cannot import MODULE. Regular expressions are searched (re.search, multi-line).
"""
import argparse
import importlib
import os
import re
import shutil
import subprocess
import sys

SKIP = 77


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--rc", type=int, required=True)
    p.add_argument("--stdout", action="append", default=[])
    p.add_argument("--not-stdout", action="append", default=[])
    p.add_argument("--stderr", action="append", default=[])
    p.add_argument("--file", action="append", default=[])
    p.add_argument("--clean", action="append", default=[])
    p.add_argument("--needs")
    p.add_argument("command", nargs="+")
    args = p.parse_args()
    if args.needs:
        try:
            importlib.import_module(args.needs)
        except ImportError:
            print("skipped: %s cannot import %s" % (sys.executable, args.needs))
            return SKIP
    for d in args.clean:
        shutil.rmtree(d, ignore_errors=True)
    proc = subprocess.run(args.command, capture_output=True, text=True)
    print(proc.stdout, end="")
    print(proc.stderr, end="", file=sys.stderr)
    errors = []
    if proc.returncode != args.rc:
        errors.append("exit status %d, expected %d" % (proc.returncode, args.rc))
    errors += ["stdout lacks /%s/" % r for r in args.stdout if not re.search(r, proc.stdout, re.M)]
    errors += ["stdout has /%s/" % r for r in args.not_stdout if re.search(r, proc.stdout, re.M)]
    errors += ["stderr lacks /%s/" % r for r in args.stderr if not re.search(r, proc.stderr, re.M)]
    errors += ["no file %s" % f for f in args.file if not os.path.isfile(f)]
    for e in errors:
        print("expect.py: " + e, file=sys.stderr)
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
