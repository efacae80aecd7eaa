#!/usr/bin/env python3
"""Regenerates the tables of figures in README.md and docs/ from the tools' --json output.

Every table of measured figures sits between two markers in a Markdown file:

    <!-- table:NAME -->
    | ... generated ... |
    <!-- /table:NAME -->

NAME is a table defined in scripts/tables/*.py: a function decorated with @table("NAME")
that reads the JSON files under docs/data/ (written by the commands each file names) and
returns the table's Markdown. This script replaces what lies between the markers with the
function's output, so a table is regenerated, never typed.

Usage: scripts/doc-tables.py          rewrite the tables in place
       scripts/doc-tables.py --check  exit 1 if a table differs from what the data gives
"""
import importlib.util
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "scripts"))
import tables  # noqa: E402  (the registry, scripts/tables/__init__.py)

MARKER = re.compile(r"(<!-- table:([\w.-]+) -->\n)(.*?)(<!-- /table:\2 -->)", re.S)


def load_definitions():
    for path in sorted((ROOT / "scripts" / "tables").glob("*.py")):
        if path.name == "__init__.py":
            continue
        spec = importlib.util.spec_from_file_location(f"tables.{path.stem}", path)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)


def rewrite(text, path):
    used = []

    def one(m):
        name = m.group(2)
        if name not in tables.REGISTRY:
            sys.exit(f"{path}: no table named {name!r} in scripts/tables/")
        used.append(name)
        body = tables.REGISTRY[name]().rstrip("\n") + "\n"
        return m.group(1) + body + m.group(4)

    return MARKER.sub(one, text), used


def main():
    check = "--check" in sys.argv[1:]
    load_definitions()
    files = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
    stale = []
    for path in files:
        text = path.read_text()
        new, used = rewrite(text, path.relative_to(ROOT))
        if new != text:
            stale.append(path.relative_to(ROOT))
            if not check:
                path.write_text(new)
        for name in used:
            print(f"{path.relative_to(ROOT)}: {name}")
    if check and stale:
        sys.exit("tables differ from docs/data: " + ", ".join(map(str, stale)))


if __name__ == "__main__":
    main()
