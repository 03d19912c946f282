"""Issue 12 point 2: every sample table with `law = "parallel_bond"` states `pb_moment_factor`
(published micro-parameters are only reusable with the beta they were calibrated with;
docs/materials.md "Bond-moment factor beta")."""
import sys
import tomllib
from pathlib import Path


def tables(node, path):
    if isinstance(node, dict):
        yield path, node
        for key, value in node.items():
            yield from tables(value, f"{path}.{key}" if path else key)
    elif isinstance(node, list):
        for i, value in enumerate(node):
            yield from tables(value, f"{path}[{i}]")


def missing_beta(root):
    for f in sorted(Path(root).rglob("*.toml")):
        with open(f, "rb") as fh:
            doc = tomllib.load(fh)
        for path, table in tables(doc, ""):
            if table.get("law") == "parallel_bond" and "pb_moment_factor" not in table:
                yield f"{f}: table [{path}] uses law = \"parallel_bond\" without pb_moment_factor"


if __name__ == "__main__":
    problems = list(missing_beta(sys.argv[1]))
    for p in problems:
        print(p, file=sys.stderr)
    sys.exit(1 if problems else 0)
