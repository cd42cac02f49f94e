#!/usr/bin/env python3
"""The case file's key reference, read from the section readers and checked against the docs.

    python3 scripts/case_keys.py --write   rewrites the reference in docs/case-file.md
    python3 scripts/case_keys.py --check   exit 1 when the reference and the readers differ

The keys are what each section reader asks its SectionReader for (apps/case/*_sections.cc,
lift_section.cc, section_reader.cc for the follower keys of [profile] (and the synthesis file's [checks]));
the unit suffixes are lib/units.cc's table. ctest runs --check (test `case_key_reference`):
a key added to a reader and not to the docs, or documented and no longer read, fails it.
"""
import pathlib
import re
import sys

from doc_block import Block, WriteOrCheck

ROOT = pathlib.Path(__file__).resolve().parent.parent
DOC = ROOT / "docs" / "case-file.md"
BEGIN = "<!-- case-keys: begin (scripts/case_keys.py --write) -->"
END = "<!-- case-keys: end -->"
READERS = ["apps/case/spring_sections.cc", "apps/case/run_sections.cc",
           "apps/case/lift_section.cc", "apps/case/section_reader.cc",
           "apps/case/sizing_section.cc"]
# Reader function -> the section(s) it reads.
SECTIONS = {"ReadNeedle": ["needle"], "ReadHelical": ["spring"], "ReadSpring": ["spring"],
            "ReadLimits": ["limits"], "ReadEngine": ["engine"], "ReadTrain": ["train"],
            "ReadSolver": ["solver"], "ReadOverspeed": ["overspeed"],
            "ReadTolerance": ["tolerance"], "ReadProfile": ["profile"], "ReadPaper": ["paper"],
            "ReadLift": ["lift"], "ReadLiftRule": ["lift"], "ReadBreaks": ["lift"],
            "ReadSplineEnds": ["lift"], "ReadFollowerKeys": ["profile"],
            "ReadSizing": ["sizing"], "ReadDesignProblem": ["sizing"]}
ORDER = ["engine", "lift", "needle", "spring", "train", "solver", "overspeed", "profile",
         "tolerance", "paper", "limits", "sizing"]
PLAIN = r"(?:OptionalNumber|OptionalStringArray|OptionalString|OptionalBool|OptionalCount|Known)"
QUANTITY = (r"(?:Quantity|OptionalQuantity|OptionalQuantityArray|FindQuantity|Positive|"
            r"OptionalPositive|sigma)")


def Units():
    text = (ROOT / "lib" / "units.cc").read_text()
    units = {}
    for m in re.finditer(r"case Dimension::k(\w+):\s*return \{(.*?)\};", text, re.S):
        units[m.group(1)] = re.findall(r'\{"(\w+)",', m.group(2))
    return units


def Functions(text):
    """(name, body) of each top-level reader function."""
    starts = [(m.start(), m.group(1)) for m in
              re.finditer(r"^\w[\w:<>]* (Read\w+)\(SectionReader", text, re.M)]
    for s, name in starts:
        yield name, text[s:text.index("\n}\n", s) + 2]  # to the function's closing brace


def Keys():
    units = Units()
    keys = {s: set() for s in ORDER}
    for f in READERS:
        for name, body in Functions((ROOT / f).read_text()):
            for section in SECTIONS.get(name, []):
                for m in re.finditer(PLAIN + r'\(\s*(?:r,\s*)?"(\w+)"', body):
                    keys[section].add((m.group(1), ""))
                for m in re.finditer(QUANTITY + r'\(\s*(?:r,\s*|ch,\s*)?"(\w+)",\s*Dimension::k(\w+)',
                                     body):
                    keys[section].add((m.group(1), m.group(2)))
                if re.search(r"\bOptionalCycle\(", body):  # the engine cycle's key
                    keys[section].add(("cycle", ""))
                # plain keys read in a loop: {"key", &member} pairs and lists of key names
                for m in re.finditer(r'\{"(\w+)", &', body):
                    keys[section].add((m.group(1), ""))
                for m in re.finditer(r'const char\* key : \{([^}]*)\}\) \{\s*if \(r\.OptionalNumber', body):
                    for k in re.findall(r'"(\w+)"', m.group(1)):
                        keys[section].add((k, ""))
                for m in re.finditer(r'\b(?:length|BoundedLength)\(\s*(?:r,\s*)?"(\w+)"', body):
                    keys[section].add((m.group(1), "Length"))
                for m in re.finditer(r'\b(?:fraction|optional_fraction)\(\s*"(\w+)"', body):
                    keys[section].add((m.group(1), "Percent"))
    lines = ["| section | key | unit suffixes |", "|---|---|---|"]
    for section in ORDER:
        for key, dim in sorted(keys[section]):
            if dim:
                suffixes = ", ".join("`_%s`" % u for u in units.get(dim, []))
                lines.append("| [%s] | `%s_…` | %s |" % (section, key, suffixes))
            else:
                lines.append("| [%s] | `%s` | — |" % (section, key))
    return "\n".join(lines)


def main():
    a = WriteOrCheck(__doc__.split("\n")[0])
    block = Block(DOC, BEGIN, END, "case_keys")
    old = block.old
    new = Keys()
    if a.write:
        block.Write(new)
        print("wrote the key reference of docs/case-file.md")
        return 0
    old_rows, new_rows = set(old.strip().splitlines()), set(new.splitlines())
    for row in sorted(old_rows - new_rows):
        print("documented, not read: " + row)
    for row in sorted(new_rows - old_rows):
        print("read, not documented: " + row)
    if old_rows != new_rows:
        print("case_keys: docs/case-file.md's key reference differs from the section readers "
              "(python3 scripts/case_keys.py --write)")
        return 1
    print("case_keys: %d keys as documented" % (len(new_rows) - 2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
