#!/usr/bin/env python3
"""The documented verdicts of the bundled cases, made by the program and checked against it.

    python3 scripts/bundled_verdicts.py --needle build/needle --write   rewrites the table in
                                                                        docs/validation.md
    python3 scripts/bundled_verdicts.py --needle build/needle --check   exit 1 when the table and
                                                                        the program disagree

Every case of cases/ that `needle check` takes (engine and synthesis files are inputs of
`design` and `synth`, not scenes) is checked with --json; its row holds the overall verdict,
what fails (a spring sub-check, a limits row, the overspeed rule, ...), n_qs and n_dyn to
0.1 rpm with the sweep's status. ctest runs --check (test `documented_verdicts`), so a verdict
written in the docs that the program no longer gives fails the suite.
"""
import json
import os
import pathlib
import subprocess
import sys
import tempfile

from doc_block import Block, WriteOrCheck

ROOT = pathlib.Path(__file__).resolve().parent.parent
DOC = ROOT / "docs" / "validation.md"
BEGIN = "<!-- bundled-verdicts: begin (scripts/bundled_verdicts.py --write) -->"
END = "<!-- bundled-verdicts: end -->"
HEADER = ["case", "verdict", "what fails", "n_qs rpm", "n_dyn rpm", "sweep"]


def Failing(d):
    out = []
    for item in d.get("failing", []):
        parts = item.split(": ")
        if parts[0] == "limits":
            continue  # named by the rows below
        if parts[0] == "spring check" and len(parts) > 1:
            out.append("spring: " + parts[1])
        else:
            out.append(parts[0])
    for row in d.get("limits") or []:
        if row.get("verdict") == "fail":
            out.append("limits: " + row["name"])
    return ", ".join(out) if out else "—"


def Rpm(v):
    return "—" if v is None else "%.1f" % v


def Rows(needle):
    rows = []
    with tempfile.TemporaryDirectory() as out:
        for case in sorted((ROOT / "cases").glob("*.toml")):
            if case.stem.endswith("-engine") or case.stem.endswith("-synth"):
                continue
            run = subprocess.run([needle, "check", str(case), "--json", "--out", out],
                                 capture_output=True, text=True)
            if run.returncode not in (0, 1):
                sys.exit("bundled_verdicts: needle check %s: exit %d: %s" %
                         (case.name, run.returncode, run.stderr.strip()))
            d = json.loads(run.stdout)
            o = d.get("overspeed") or {}
            rows.append([case.name, d["overall"], Failing(d), Rpm(o.get("liftoff_rpm_quasi_static")),
                         Rpm(o.get("liftoff_rpm_dynamic")), o.get("status", "—")])
    return rows


def Table(rows):
    lines = ["| " + " | ".join(HEADER) + " |", "|" + "---|" * len(HEADER)]
    lines += ["| " + " | ".join(r) + " |" for r in rows]
    return "\n".join(lines)


def main():
    a = WriteOrCheck(__doc__.split("\n")[0], lambda p: p.add_argument(
        "--needle", default=str(ROOT / "build" / "needle")))
    block = Block(DOC, BEGIN, END, "bundled_verdicts")
    old = block.old
    new = Table(Rows(a.needle))
    if a.write:
        block.Write(new)
        print("wrote the table of %s" % DOC.relative_to(ROOT))
        return 0
    documented = old.strip().splitlines()
    program = new.splitlines()
    bad = [("docs: " + d, "program: " + n) for d, n in zip(documented, program) if d != n]
    if len(documented) != len(program):
        bad.append(("docs: %d rows" % len(documented), "program: %d rows" % len(program)))
    for d, n in bad:
        print(d + "\n" + n)
    if bad:
        print("bundled_verdicts: docs/validation.md no longer matches the program "
              "(python3 scripts/bundled_verdicts.py --write, then explain the change)")
        return 1
    print("bundled_verdicts: %d cases as documented" % (len(program) - 2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
