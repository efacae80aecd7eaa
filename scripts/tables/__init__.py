"""The registry of generated tables and the helpers their definitions share.

A definition file (scripts/tables/<topic>.py) registers each table with @table("name");
scripts/doc-tables.py fills the markers <!-- table:name --> ... <!-- /table:name -->.
"""
import json
import pathlib

DATA = pathlib.Path(__file__).resolve().parent.parent.parent / "docs" / "data"
REGISTRY = {}


def table(name):
    """Registers the decorated function as the table `name`."""

    def register(f):
        if name in REGISTRY:
            raise SystemExit(f"table {name!r} is defined twice")
        REGISTRY[name] = f
        return f

    return register


def load_jsonl(name):
    """The JSON objects of docs/data/NAME, one per line (a .json file holds one object)."""
    text = (DATA / name).read_text()
    if name.endswith(".json"):
        return [json.loads(text)]
    return [json.loads(line) for line in text.splitlines() if line.strip()]


def markdown(header, rows, align=None):
    """A Markdown table: `header` a list of column titles, `rows` lists of cells (str())."""
    align = align or ["---"] * len(header)
    out = ["| " + " | ".join(header) + " |", "|" + "|".join(align) + "|"]
    for r in rows:
        out.append("| " + " | ".join("" if c is None else str(c) for c in r) + " |")
    return "\n".join(out) + "\n"


def fmt(v, spec):
    """`v` formatted with `spec` ('.1f', 'd', ','), or '—' for None."""
    if v is None:
        return "—"
    if spec == ",":
        return f"{v:,}".replace(",", " ")
    return format(v, spec)
