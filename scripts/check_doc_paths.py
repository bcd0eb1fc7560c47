#!/usr/bin/env python3
"""Checks that the markdown files name only files that exist: every path under lib/, apps/,
include/, kernels/, tests/, scripts/, python/, fuzz/, docs/ or cmake/ (at the repository root, or
after ../ relative to the markdown file), and the relative target of every markdown link or image.
Globs match against the tree (lib/cluster_*.*, apps/bench_runs.\\*), and each alternative of a
{hpp,cpp} group must exist. A path inside another path (build/apps/relume, PREFIX/lib/...) is not
a repository path and is left alone. Exits 1 listing file:line and each path that names nothing.

Usage: scripts/check_doc_paths.py [REPOSITORY_ROOT [MARKDOWN_FILE ...]]
  (without files: every markdown file of the repository, as git lists it)
"""
import glob
import os
import pathlib
import re
import subprocess
import sys

ROOTS = ("lib", "apps", "include", "kernels", "tests", "scripts", "python", "fuzz", "docs", "cmake")
# A root folder not preceded by a path or word character, then path characters: letters, digits,
# _ . - / *, a markdown-escaped \* or \_, and {a,b} groups.
PATH = re.compile(r"(?<![\w./~$-])((?:\.\./)*(?:" + "|".join(ROOTS) + r")/"
                  r"(?:[\w.*/-]|\\[*_]|\{[\w.,]*\})*)")
LINK = re.compile(r"\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
BRACES = re.compile(r"\{([\w.,]*)\}")


def markdown_files(root):
    try:
        listed = subprocess.run(["git", "ls-files", "-co", "--exclude-standard", "*.md"], cwd=root,
                                capture_output=True, text=True, check=True).stdout.split()
        return [root / name for name in listed if (root / name).is_file()]
    except (OSError, subprocess.CalledProcessError):
        found = []
        for folder, subfolders, files in os.walk(root):
            subfolders[:] = [s for s in subfolders if not s.startswith((".", "build"))]
            found += [pathlib.Path(folder) / f for f in files if f.endswith(".md")]
        return found


def alternatives(path):
    """lib/a.{hpp,cpp} -> [lib/a.hpp, lib/a.cpp]."""
    match = BRACES.search(path)
    if not match:
        return [path]
    return [expanded for choice in match.group(1).split(",")
            for expanded in alternatives(path[:match.start()] + choice + path[match.end():])]


def exists(base, path):
    for alternative in alternatives(path):
        if "*" in alternative:
            if not glob.glob(alternative, root_dir=base):
                return False
        elif not (base / alternative).exists():
            return False
    return True


def named_paths(line):
    """(path, folder it is relative to: 'root' or 'file') of each path the line names."""
    for match in PATH.finditer(line):
        path = re.sub(r"\\([*_])", r"\1", match.group(1)).rstrip(".")
        yield path, "file" if path.startswith("../") else "root"
    for match in LINK.finditer(line):
        target = match.group(1).split("#")[0]
        if target and not re.match(r"[a-z][a-z0-9+.-]*:", target) and not target.startswith("/"):
            yield target, "file"


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parent.parent)
    root = root.resolve()
    files = [pathlib.Path(f).resolve() for f in sys.argv[2:]] or markdown_files(root)
    problems, checked = [], 0
    for markdown in sorted(files):
        shown = markdown.relative_to(root) if markdown.is_relative_to(root) else markdown
        for number, line in enumerate(markdown.read_text().splitlines(), 1):
            for path, relative_to in dict.fromkeys(named_paths(line)):
                checked += 1
                if not exists(root if relative_to == "root" else markdown.parent, path):
                    problems.append(f"{shown}:{number}: {path} does not exist")
    for problem in problems:
        print(problem, file=sys.stderr)
    if problems:
        print(f"check_doc_paths: {len(problems)} of {checked} named paths do not exist; name the "
              "file where it lives now", file=sys.stderr)
        return 1
    print(f"check_doc_paths: {len(files)} markdown files name {checked} paths, all present")
    return 0


if __name__ == "__main__":
    sys.exit(main())
