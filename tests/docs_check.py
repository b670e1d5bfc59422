#!/usr/bin/env python3
"""The docs are true to the code: what README.md and docs/*.md cite exists.

usage: tests/docs_check.py REPO_ROOT BUILD_DIR [--readme FILE]

Fails (exit 1, one `FILE:LINE: problem` line per offence) when
1. the option names (`--word`) of the fenced block under "## The program" in README.md
   and those `BUILD_DIR/cxx/mpm3d --help` prints differ, either way;
2. a repository path the docs cite does not exist: a backticked span or a bare word that
   starts with a top-level folder (cxx/ fortran_ref/ bindings/ tests/ inputs/ docs/
   tools/ .ci/) or is Makefile / CMakeLists.txt; a backticked span whose first component
   is a folder of cxx/ (`core/step_state.hpp`, docs/ARCHITECTURE.md's style) is looked
   up under cxx/. Globs (`*`, `?`, `core/particle.*`) need one match, brace lists
   (`data_in*.{hpp,cpp}`) expand, each alternative must exist. Trailing `.,;:)` is not
   part of a path; spans holding spaces, `<`, `>`, `$`, `=` or `...` are not paths
   (their words are still read as bare words);
3. `make X` (in a backticked span or a fenced code block) names no target of Makefile;
4. a backticked test name (`threads.name`, `ranks.*`, ..., or GoogleTest's `Suite.Name`,
   `Family/Suite.Name/param`, `Suite.*`) matches no name of `ctest -N` in BUILD_DIR
   (`*` a wildcard). Spans that occur in the C++ sources (`ranks.order`, a member) and
   file names (`threads.cmake`, `Taylor.out`) are not test names. A family the build left
   out (GoogleTest's suites without GoogleTest, `ranks.*` without MPI) is not checked.
docs/bench/ and the other folders of docs/ (generated results) are not read.
With --readme FILE, FILE is read in place of README.md (to test this script).
"""
import collections
import fnmatch
import glob
import os
import re
import subprocess
import sys

TOP_FOLDERS = ("cxx/", "fortran_ref/", "bindings/", "tests/", "inputs/", "docs/", "tools/", ".ci/")
TOP_FILES = ("Makefile", "CMakeLists.txt")
TEST_PREFIXES = ("threads", "ranks", "restart", "output", "paraview", "bindings", "layers", "docs")
# `threads.cmake`, `restart.h5`: files, not tests.
FILE_SUFFIXES = {"cmake", "h5", "json", "py", "sh", "txt", "md", "dat", "csv", "xdmf", "vtu",
                 "pvd", "out", "mpm", "cpp", "hpp", "f90", "c", "h", "png", "tmp"}
SPAN_RE = re.compile(r"`([^`\n]+)`")
OPTION_RE = re.compile(r"--[a-z][a-z0-9-]*")
MAKE_RE = re.compile(r"\bmake\s+([a-z][a-z-]*)\b")
PREFIX_TEST_RE = re.compile(r"(%s)\.[A-Za-z0-9_*]+(\.[A-Za-z0-9_*]+)*$" % "|".join(TEST_PREFIXES))
CAMEL = r"[A-Z][A-Za-z0-9_]*[a-z][A-Za-z0-9_]*"
GTEST_RE = re.compile(r"(%s/)?%s\.(%s|\*)(/[A-Za-z0-9_*\"]+)?$" % (CAMEL, CAMEL, CAMEL))


def family(test):
    """GoogleTest's names, or the prefix of a script test (`ranks` of `ranks.usl_blocks`)."""
    return "GoogleTest" if test[0].isupper() else test.split(".")[0]


def doc_lines(root, readme):
    """(shown name, line number, text, inside a fenced block) for every line read."""
    files = [(readme, shown_readme(root, readme))]
    for path in sorted(glob.glob(os.path.join(root, "docs", "*.md"))):
        files.append((path, os.path.relpath(path, root)))
    for path, shown in files:
        fenced = False
        with open(path, encoding="utf-8") as f:
            for number, line in enumerate(f, 1):
                if line.lstrip().startswith("```"):
                    fenced = not fenced
                    continue
                yield shown, number, line.rstrip("\n"), fenced


def shown_readme(root, readme):
    return "README.md" if readme == os.path.join(root, "README.md") else readme


def check_options(root, build, readme, offences):
    """1. README's option block against mpm3d --help, both ways."""
    lines = open(readme, encoding="utf-8").read().split("\n")
    shown = shown_readme(root, readme)
    start = next((i for i, l in enumerate(lines) if l.strip() == "## The program"), None)
    if start is None:
        offences.append("%s:1: no '## The program' heading" % shown)
        return
    section_end = next((i for i in range(start + 1, len(lines)) if lines[i].startswith("## ")),
                       len(lines))
    fences = [i for i in range(start, section_end) if lines[i].lstrip().startswith("```")]
    if len(fences) < 2:
        offences.append("%s:%d: no fenced block under '## The program'" % (shown, start + 1))
        return
    fence, end = fences[0], fences[1]
    cited = {}
    for i in range(fence + 1, end):
        for option in OPTION_RE.findall(lines[i]):
            cited.setdefault(option, i + 1)
    exe = os.path.join(build, "cxx", "mpm3d")
    try:
        run = subprocess.run([exe, "--help"], capture_output=True, text=True)
    except OSError as e:
        offences.append("%s:0: cannot run: %s" % (exe, e))
        return
    if run.returncode != 0:
        offences.append("%s:0: `mpm3d --help` exited %d" % (exe, run.returncode))
        return
    printed = set(OPTION_RE.findall(run.stdout + run.stderr))
    for option in sorted(printed - set(cited)):
        offences.append("%s:%d: option %s of `mpm3d --help` is missing from the block"
                        % (shown, fence + 1, option))
    for option in sorted(set(cited) - printed):
        offences.append("%s:%d: option %s is not in `mpm3d --help`" % (shown, cited[option], option))


def expand_braces(path):
    m = re.search(r"\{([^{}]*)\}", path)
    if not m:
        return [path]
    return [e for alt in m.group(1).split(",")
            for e in expand_braces(path[:m.start()] + alt + path[m.end():])]


def path_exists(root, path):
    for each in expand_braces(path):
        full = os.path.join(root, each)
        if not (glob.glob(full) if any(c in each for c in "*?[") else os.path.exists(full)):
            return False
    return True


def cited_paths(line, cxx_folders):
    """(path as written, path relative to the root) for the repository paths of a line."""
    skip = ("<", ">", "$", "=", "...")
    for span in SPAN_RE.findall(line):
        span = span.rstrip(".,;:)")
        if " " in span or any(s in span for s in skip):
            continue
        if span.split("/")[0] in cxx_folders and "/" in span:
            yield span, "cxx/" + span
    for word in re.split(r"[\s`]+", line):
        word = word.lstrip("(\"'").rstrip(".,;:)\"'")
        if any(s in word for s in skip):
            continue
        if word.startswith(TOP_FOLDERS) or word in TOP_FILES:
            yield word, word


def check_docs(root, build, readme, offences, counts):
    """2., 3. and 4. over README.md and docs/*.md."""
    cxx_folders = {d for d in os.listdir(os.path.join(root, "cxx"))
                   if os.path.isdir(os.path.join(root, "cxx", d))}
    makefile = open(os.path.join(root, "Makefile"), encoding="utf-8").read()
    targets = set(re.findall(r"^([a-z][a-z-]*)\s*:(?!=)", makefile, re.M))
    for phony in re.findall(r"^\.PHONY\s*:(.*)$", makefile, re.M):
        targets.update(phony.split())
    ctest = subprocess.run(["ctest", "-N"], cwd=build, capture_output=True, text=True)
    tests = re.findall(r"^\s*Test\s+#\d+:\s+(\S+)", ctest.stdout, re.M)
    if not tests:
        offences.append("%s:0: `ctest -N` lists no tests" % build)
    families = {family(t) for t in tests}
    sources = "".join(open(p, encoding="utf-8", errors="replace").read()
                      for p in glob.glob(os.path.join(root, "cxx", "**", "*.[ch]*"), recursive=True))
    for shown, number, line, fenced in doc_lines(root, readme):
        where = "%s:%d:" % (shown, number)
        for written, path in cited_paths(line, cxx_folders):
            counts["paths"] += 1
            if not path_exists(root, path):
                offences.append("%s path %s does not exist" % (where, written))
        for text in ([line] if fenced else SPAN_RE.findall(line)):
            if "make -C" in text or "make -f" in text:
                continue
            for target in MAKE_RE.findall(text):
                counts["make targets"] += 1
                if target not in targets:
                    offences.append("%s `make %s`: no such target in Makefile" % (where, target))
        for span in SPAN_RE.findall(line):
            prefix = PREFIX_TEST_RE.match(span)
            if not (prefix or GTEST_RE.match(span)) or family(span) not in families or \
                    prefix and span.rsplit(".", 1)[1] in FILE_SUFFIXES or \
                    "*" not in span and re.search(r"\b%s\b" % re.escape(span), sources):
                continue
            counts["test names"] += 1
            if not fnmatch.filter(tests, span):
                offences.append("%s test %s matches no test of `ctest -N`" % (where, span))


def main():
    args = sys.argv[1:]
    readme = None
    if "--readme" in args:
        i = args.index("--readme")
        readme = os.path.abspath(args[i + 1])
        del args[i:i + 2]
    if len(args) != 2:
        sys.exit(__doc__)
    root, build = (os.path.abspath(a) for a in args)
    readme = readme or os.path.join(root, "README.md")
    offences = []
    check_options(root, build, readme, offences)
    counts = collections.Counter()
    check_docs(root, build, readme, offences, counts)
    if offences:
        print("\n".join(offences))
        print("docs_check: %d offence(s)" % len(offences))
        return 1
    print("docs_check: README's options match mpm3d --help; %d cited paths, %d make targets "
          "and %d test names exist" % (counts["paths"], counts["make targets"], counts["test names"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
