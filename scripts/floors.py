#!/usr/bin/env python3
"""The dependency rule of docs/architecture.md, checked: no #include runs up a floor; and the
sizes issue 34 set: no source file over 500 lines, no command file (apps/cli) over 200; and
issue 52's rule: apps/study and apps/report never include the file model (case_file.h).

The floors, lowest first; a file may include its own floor's headers and those of any floor
below it, never one above (nor a sibling: cli and python do not include each other, bench
includes no writer). Inside dynamics/, model ◂ solver ◂ the top (simulation, overspeed).

    python3 scripts/floors.py     lists every include that runs up, exit 1 when there is one
"""
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent

# floor → the floors it may include (besides itself)
BELOW = {
    "lib": [],
    "spring": ["lib"],
    "dynamics/model": ["lib", "spring"],
    "dynamics/solver": ["lib", "spring", "dynamics/model"],
    "dynamics": ["lib", "spring", "dynamics/model", "dynamics/solver"],
    "apps/case": ["lib", "spring", "dynamics/model", "dynamics/solver", "dynamics"],
}
BELOW["apps/study"] = BELOW["apps/case"] + ["apps/case"]
BELOW["apps/bench"] = BELOW["apps/study"] + ["apps/study"]
BELOW["apps/report"] = BELOW["apps/study"] + ["apps/study"]
BELOW["apps/cli"] = BELOW["apps/report"] + ["apps/report"]
BELOW["apps/python"] = BELOW["apps/report"] + ["apps/report"]

# The file model (issue 52): the study and report floors read a bound case (apps/case/
# bound_case.h, Bind), never these, directly or through another apps/case header.
FILE_MODEL = {"apps/case/case_file.h", "apps/case/case_scene.h", "apps/case/section_reader.h"}
BOUND_ONLY = ("apps/study", "apps/report")
# Where Method's enumerators are named: its declaration and the method table.
METHOD_TABLE = {"dynamics/solver/integrator.h", "dynamics/solver/methods.cc"}


def Includes(rel: str):
    """The quoted includes of a repository file ([] when it is not there)."""
    path = ROOT / rel
    if not path.is_file():
        return []
    return re.findall(r'^\s*#\s*include\s+"([^"]+)"', path.read_text(encoding="utf-8"), re.M)


def FileModelVia(target: str, seen=None):
    """The chain by which header `target` reaches the file model, or None."""
    seen = set() if seen is None else seen
    if target in FILE_MODEL:
        return [target]
    if target in seen or not target.startswith("apps/case/"):
        return None
    seen.add(target)
    for inner in Includes(target):
        chain = FileModelVia(inner, seen)
        if chain:
            return [target] + chain
    return None


def FloorOf(path: str):
    """The floor of a repository path (the longest floor prefix), or None outside them."""
    best = None
    for floor in BELOW:
        if path.startswith(floor + "/") and (best is None or len(floor) > len(best)):
            best = floor
    return best


def main() -> int:
    include = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
    bad = []
    files = 0
    for source in sorted(ROOT.glob("**/*")):
        rel = source.relative_to(ROOT).as_posix()
        if source.suffix not in (".h", ".cc") or rel.startswith(("build", "tests/", ".")):
            continue
        floor = FloorOf(rel)
        if floor is None:
            continue
        files += 1
        text = source.read_text(encoding="utf-8")
        lines = text.count("\n")
        most = 200 if floor == "apps/cli" else 500
        if lines > most:
            bad.append(f"{rel}: {lines} lines, more than {most}")
        # The method table carries the methods' capabilities (issue 52): no enumerator of Method
        # is named outside it.
        if "Method::k" in text and rel not in METHOD_TABLE:
            bad.append(f"{rel}: names a Method enumerator; read the method table "
                       "(dynamics/solver/integrator.h: MethodIsClosedForm, AutoMethodFor, …)")
        for target in include.findall(text):
            to = FloorOf(target)
            if to is not None and to != floor and to not in BELOW[floor]:
                bad.append(f"{rel}: includes {target} ({to} is not below {floor})")
            chain = FileModelVia(target) if floor in BOUND_ONLY else None
            if chain:
                bad.append(f"{rel}: includes the file model ({' -> '.join(chain)}); "
                           "read the bound case (apps/case/bound_case.h)")
    for line in bad:
        print(line)
    print(f"floors: {files} files, {len(bad)} includes running up a floor or files too long")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
