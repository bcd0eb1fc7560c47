#!/usr/bin/env python3
"""Checks that lib/'s dependencies point one way (lib/README.md): every include in lib/<folder>/
names only that folder, a folder of its "may use" column, or a public header <relume/x.hpp>
implemented by one of those, and the "may use" graph has no cycle. Exits 1 naming each violation
(file, line, include, and what the folder may use).

Usage: scripts/check_layers.py [REPOSITORY_ROOT]
"""
import pathlib
import re
import sys

ROW = re.compile(r"^\| `([a-z0-9_]+)/` \|[^|]*\|([^|]*)\|([^|]*)\|\s*$")
INCLUDE = re.compile(r'^\s*#\s*include\s+(?:"([a-z0-9_]+)/[^"]+"|<relume/([a-z0-9_]+)\.hpp>)')


def read_table(readme):
    allowed, implements = {}, {}
    for line in readme.read_text().splitlines():
        match = ROW.match(line)
        if not match:
            continue
        folder = match.group(1)
        allowed[folder] = {name.strip() for name in match.group(3).split(",") if name.strip()}
        for header in re.findall(r"`([a-z0-9_]+)\.hpp`", match.group(2)):
            implements[header] = folder
    return allowed, implements


def find_cycle(allowed):
    state = {}

    def visit(folder, path):
        state[folder] = "open"
        for used in sorted(allowed.get(folder, ())):
            if state.get(used) == "open":
                return path + [used]
            if used not in state:
                cycle = visit(used, path + [used])
                if cycle:
                    return cycle
        state[folder] = "done"
        return None

    for folder in sorted(allowed):
        if folder not in state:
            cycle = visit(folder, [folder])
            if cycle:
                return cycle
    return None


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parent.parent)
    lib = root / "lib"
    allowed, implements = read_table(lib / "README.md")
    problems = []
    if not allowed:
        problems.append(f"{lib / 'README.md'}: no folder table found")
    for folder, uses in allowed.items():
        for used in uses - allowed.keys():
            problems.append(f"lib/README.md: {folder}/ may use '{used}', which is not a folder of the table")
    cycle = find_cycle(allowed)
    if cycle:
        problems.append("lib/README.md: the 'may use' column has a cycle: " + " -> ".join(cycle))
    for path in sorted(lib.iterdir()):
        if path.is_file() and path.suffix in (".cpp", ".hpp"):
            problems.append(f"{path.relative_to(root)}: a source file directly in lib/ (it belongs in a stage folder)")
        if path.is_dir() and path.name not in allowed:
            problems.append(f"{path.relative_to(root)}/: a folder lib/README.md does not describe")
    for folder, uses in sorted(allowed.items()):
        for source in sorted((lib / folder).glob("*.[ch]pp")):
            for number, line in enumerate(source.read_text().splitlines(), 1):
                match = INCLUDE.match(line)
                if not match:
                    continue
                internal, public = match.groups()
                where = f"{source.relative_to(root)}:{number}"
                if public == "relume":
                    problems.append(f"{where}: includes the umbrella header <relume/relume.hpp>")
                    continue
                if public is not None and public not in implements:
                    problems.append(f"{where}: <relume/{public}.hpp> is not listed as implemented "
                                    "by any folder in lib/README.md")
                    continue
                used = internal if internal is not None else implements[public]
                if internal is not None and internal not in allowed:
                    continue  # a system or third-party path such as "CL/..." is not a stage
                if used != folder and used not in uses:
                    problems.append(f"{where}: {line.strip()} uses {used}/, but {folder}/ may use "
                                    f"only: {', '.join(sorted(uses)) or 'nothing'}")
    for problem in problems:
        print(problem, file=sys.stderr)
    if problems:
        return 1
    print(f"check_layers: {len(allowed)} folders, dependencies point one way")
    return 0


if __name__ == "__main__":
    sys.exit(main())
