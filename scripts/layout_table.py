#!/usr/bin/env python3
"""The layout table of docs/architecture.md: every source folder, its files and lines, and the
largest file; written from the tree and checked against it.

    python3 scripts/layout_table.py --write   rewrites the table
    python3 scripts/layout_table.py --check   exit 1 when the table and the tree differ in
                                              the folders or their file counts (test
                                              `layout_table`); line counts are reported, not
                                              checked, so an edit need not rewrite the page
"""
import pathlib
import re
import sys

from doc_block import Block, WriteOrCheck

ROOT = pathlib.Path(__file__).resolve().parent.parent
DOC = ROOT / "docs" / "architecture.md"
BEGIN = "<!-- layout-table: begin (scripts/layout_table.py --write) -->"
END = "<!-- layout-table: end -->"
TOPS = ["lib", "spring", "dynamics", "apps"]
EXT = {".h", ".cc", ".py", ".txt"}


def Rows():
    rows = []
    for top in TOPS:
        # npm's packages (apps/serve/web/node_modules, installed by setup.sh --tests) are no
        # source: the table is the same with or without them.
        folders = sorted({p.parent for p in (ROOT / top).rglob("*")
                          if p.suffix in EXT and "node_modules" not in p.relative_to(ROOT).parts})
        for folder in folders:
            files = sorted(p for p in folder.iterdir() if p.is_file() and p.suffix in EXT)
            if not files:
                continue
            lines = {p: len(p.read_text().splitlines()) for p in files}
            big = max(files, key=lambda p: lines[p])
            rows.append((str(folder.relative_to(ROOT)) + "/", len(files), sum(lines.values()),
                         "%s (%d)" % (big.name, lines[big])))
    return rows


def Table(rows):
    out = ["| folder | files | lines | largest file (lines) |", "|---|---|---|---|"]
    out += ["| `%s` | %d | %d | %s |" % r for r in rows]
    return "\n".join(out)


def main():
    a = WriteOrCheck(__doc__.split("\n")[0])
    block = Block(DOC, BEGIN, END, "layout_table")
    old = block.old
    rows = Rows()
    if a.write:
        block.Write(Table(rows))
        print("wrote the layout table of docs/architecture.md")
        return 0
    documented = {m.group(1): int(m.group(2))
                  for m in re.finditer(r"^\| `([^`]+)` \| (\d+) \|", old, re.M)}
    actual = {r[0]: r[1] for r in rows}
    if documented != actual:
        for k in sorted(set(documented) | set(actual)):
            if documented.get(k) != actual.get(k):
                print("%s: documented %s files, the tree has %s" % (k, documented.get(k),
                                                                     actual.get(k)))
        print("layout_table: docs/architecture.md's layout table differs from the tree "
              "(python3 scripts/layout_table.py --write)")
        return 1
    print("layout_table: %d folders as documented" % len(actual))
    return 0


if __name__ == "__main__":
    sys.exit(main())
