#!/usr/bin/env python3
"""How many translation units a header reaches: the ones ninja would rebuild if it changed.

Reads the dependency log of a built tree (`ninja -t deps`, what the compiler's -MD wrote), so
it counts what really includes the header, directly or not. Prints, per header, the object
files that depend on it, as a count and a share of all object files.

    python3 bench/compile/header_fanin.py build common/scene.h common/scene_zones.h
    python3 bench/compile/header_fanin.py build --glob 'common/scene*.h'
"""
import argparse
import fnmatch
import os
import subprocess
import sys


def deps(build):
    """{object file: set of source-relative paths it depends on}."""
    out = subprocess.run(["ninja", "-C", build, "-t", "deps"], check=True,
                         capture_output=True, text=True).stdout
    root = os.path.realpath(os.path.join(build, ".."))
    table, current = {}, None
    for line in out.splitlines():
        if not line.strip():
            current = None
            continue
        if not line.startswith(" "):
            target = line.split(":")[0]
            current = table.setdefault(target, set()) if target.endswith(".o") else None
        elif current is not None:
            path = os.path.realpath(os.path.join(build, line.strip()))
            if path.startswith(root + os.sep):
                current.add(os.path.relpath(path, root))
    return table


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("build", help="a built build folder (ninja)")
    ap.add_argument("headers", nargs="*", help="headers, relative to the source root")
    ap.add_argument("--glob", help="every header matching this pattern, e.g. 'common/scene*.h'")
    args = ap.parse_args()
    table = deps(args.build)
    if not table:
        sys.exit(f"{args.build}: no dependency log; build the tree first")
    headers = list(args.headers)
    if args.glob:
        every = set().union(*table.values())
        headers += sorted(h for h in every if fnmatch.fnmatch(h, args.glob))
    if not headers:
        sys.exit("name at least one header, or --glob")
    total = len(table)
    print(f"{total} object files")
    print(f"{'header':40s} {'objects':>8s} {'share':>7s}")
    for h in headers:
        n = sum(1 for d in table.values() if h in d)
        print(f"{h:40s} {n:8d} {100.0 * n / total:6.1f}%")


if __name__ == "__main__":
    main()
