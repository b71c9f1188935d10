#!/usr/bin/env python3
"""Checks that the README and the docs stay true to the tree and the API.

    check_docs.py links [--repo DIR]
        Every relative link and image of README.md, doc/*.md and the tutorials
        (modules/rcme/tutorials/**/*.markdown) resolves to a file or folder of the repository,
        and every path the pages name in backquotes (a name with a file extension, or ending
        in '/') exists: a path with a folder relative to the repository root or to a folder of
        the module; a bare file name anywhere in the repository.

    check_docs.py cxx --compiler CXX --flags "FLAGS" --libs "LIBS" --work DIR [FILE.md...]
        Compiles every fenced ```cpp block of the files (default: README.md and the tutorials) as
        one program against the built library and runs it; a block must be a whole program.

Exit status 1 with one line per problem (file:line: what)."""

import argparse
import glob
import os
import re
import shlex
import subprocess
import sys

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))

# Folders a path in backquotes may be relative to, besides the repository root: the pages name
# the module's files from the module, its sources or its include folder.
PATH_BASES = ["", "modules", "modules/rcme", "modules/rcme/src", "modules/rcme/include",
              "modules/rcme/include/opencv2", "modules/rcme/misc", "samples"]
EXTENSIONS = ("cpp", "hpp", "h", "py", "pyi", "sh", "md", "txt", "cmake", "inc", "toml", "png",
              "jpg", "bib", "dox", "markdown", "json", "csv", "in")
# Paths of other trees, generated files and names that only look like paths (benchmark names of
# the perf suite, a placeholder folder), which the pages name on purpose.
NOT_OURS = re.compile(r"^(build[-\w]*/|<|~|/|\$|\.\./|\.\w|-)"    # generated, placeholders, options
                      r"|^(modules/(python|3d|geometry)\b|3rdparty/|CMakeDownloadLog\.txt$)"  # OpenCV's tree
                      r"|^(opencv|opencv_contrib)/$"               # the sdist's two trees
                      r"|^(opencv2/)?(opencv_modules|core|ts|geometry|3d|calib3d|features2d"
                      r"|features)\.hpp$"                          # OpenCV's headers
                      r"|^rcmeConfig\.cmake$"                      # written by the install
                      r"|^(solver|call|parallel|score-per-point)/"  # perf suite benchmark names
                      r"|^[A-Z]+/"                                  # FOLDER/K.txt
                      r"|^__init__\.pyi$")                          # the stub the build writes
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
CODE = re.compile(r"`([^`\n]+)`")
FENCE = re.compile(r"^```.*?^```", re.S | re.M)


def pages(repo):
    files = ["README.md"] + sorted(glob.glob("doc/*.md", root_dir=repo))
    files += sorted(glob.glob("modules/rcme/tutorials/**/*.markdown", root_dir=repo,
                              recursive=True))
    return files


def line_of(text, offset):
    return text.count("\n", 0, offset) + 1


def repository_names(repo):
    """The names of the repository's files and of its folders (build folders left out)."""
    files, folders = set(), set()
    for _, dirs, names in os.walk(repo):
        dirs[:] = [d for d in dirs if not d.startswith((".", "build"))]
        files.update(names)
        folders.update(dirs)
    return files, folders


def check_links(repo):
    problems = []
    basenames, folders = repository_names(repo)
    for page in pages(repo):
        text = open(os.path.join(repo, page), encoding="utf-8").read()
        here = os.path.dirname(os.path.join(repo, page))
        for match in LINK.finditer(text):
            target = match.group(1)
            if re.match(r"^[a-z]+:", target) or target.startswith("#"):
                continue
            path = target.split("#")[0]
            if not os.path.exists(os.path.join(here, path)):
                problems.append("%s:%d: link to %s, which does not exist"
                                % (page, line_of(text, match.start()), target))
        prose = FENCE.sub(lambda m: "\n" * m.group(0).count("\n"), text)
        for match in CODE.finditer(prose):
            token = match.group(1).strip().rstrip(".,;:")
            if not re.fullmatch(r"[\w./+-]+", token) or NOT_OURS.search(token):
                continue
            if not (token.endswith("/") or
                    "." in token and token.rsplit(".", 1)[-1] in EXTENSIONS):
                continue
            if "/" in token.rstrip("/"):
                found = any(os.path.exists(os.path.join(repo, base, token)) for base in PATH_BASES)
            elif token.endswith("/"):
                found = token.rstrip("/") in folders
            else:
                found = token in basenames
            if not found:
                problems.append("%s:%d: names `%s`, which is not in the repository"
                                % (page, line_of(prose, match.start()), token))
    return problems


def check_cxx(args):
    files = args.files or ["README.md"] + sorted(
        glob.glob("modules/rcme/tutorials/**/*.markdown", root_dir=REPO, recursive=True))
    os.makedirs(args.work, exist_ok=True)
    problems, count = [], 0
    for page in files:
        path = page if os.path.isabs(page) else os.path.join(REPO, page)
        text = open(path, encoding="utf-8").read()
        for index, match in enumerate(re.finditer(r"^```cpp\n(.*?)^```", text, re.S | re.M)):
            where = "%s:%d" % (os.path.relpath(path, REPO), line_of(text, match.start()) + 1)
            stem = re.sub(r"\W", "_", os.path.relpath(path, REPO)) + "_%d" % index
            source = os.path.join(args.work, stem + ".cpp")
            binary = os.path.join(args.work, stem)
            with open(source, "w", encoding="utf-8") as f:
                f.write('#line %d "%s"\n' % (line_of(text, match.start()) + 1, where.split(":")[0]))
                f.write(match.group(1))
            command = [args.compiler, "-std=c++17", "-o", binary, source]
            command += shlex.split(args.flags) + shlex.split(args.libs)
            result = subprocess.run(command, capture_output=True, text=True)
            if result.returncode != 0:
                problems.append("%s: the C++ block does not compile:\n%s" % (where, result.stderr))
                continue
            result = subprocess.run([binary], capture_output=True, text=True, timeout=120)
            if result.returncode != 0:
                problems.append("%s: the C++ block's program exited with %d:\n%s%s"
                                % (where, result.returncode, result.stdout, result.stderr))
                continue
            print("ok %s (compiled and ran)" % where)
            count += 1
    if count == 0 and not problems:
        problems.append("no C++ block in %s" % " ".join(files))
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="mode", required=True)
    links = sub.add_parser("links")
    links.add_argument("--repo", default=REPO)
    cxx = sub.add_parser("cxx")
    cxx.add_argument("--compiler", required=True)
    cxx.add_argument("--flags", default="")
    cxx.add_argument("--libs", default="")
    cxx.add_argument("--work", required=True)
    cxx.add_argument("files", nargs="*")
    args = parser.parse_args()
    if args.mode == "links":
        problems = check_links(os.path.abspath(args.repo))
        if not problems:
            print("ok: every link and named path of %d pages exists" % len(pages(args.repo)))
    else:
        problems = check_cxx(args)
    for problem in problems:
        print(problem, file=sys.stderr)
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
