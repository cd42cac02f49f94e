#!/usr/bin/env python3
"""The dependency rule of docs/architecture.md, checked: no #include runs up a floor; and the
sizes issue 34 set: no source file over 500 lines, no command file (apps/cli) over 200; and
issue 52's rules: apps/study and apps/report never include the file model (case_file.h), no
Method enumerator is named outside the method table, and no function is over 100 lines but
those LONG_FUNCTIONS lists, each at most as long as it is listed (the target is none).

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
BELOW["apps/bench"] = BELOW["apps/study"] + ["apps/study", "apps/report", "apps/serve"]
BELOW["apps/report"] = BELOW["apps/study"] + ["apps/study"]
BELOW["apps/serve"] = BELOW["apps/report"] + ["apps/report"]
BELOW["apps/cli"] = BELOW["apps/report"] + ["apps/report", "apps/serve"]
BELOW["apps/python"] = BELOW["apps/report"] + ["apps/report"]

# The file model (issue 52): the study and report floors read a bound case (apps/case/
# bound_case.h, Bind), never these, directly or through another apps/case header.
FILE_MODEL = {"apps/case/case_file.h", "apps/case/case_scene.h", "apps/case/section_reader.h"}
BOUND_ONLY = ("apps/study", "apps/report")
# Where Method's enumerators are named: its declaration and the method table.
METHOD_TABLE = {"dynamics/solver/integrator.h", "dynamics/solver/methods.cc"}


# Issue 52's target is no function over 100 lines (outside tests). These remain, each capped at
# its length when the rule came in: one may shrink or go, none may grow, and none may join.
MOST_LINES = 100
LONG_FUNCTIONS = {
}
DECLARATION = re.compile(r"(namespace|struct|class|enum|union|if|for|while|switch|do|else|return|"
                         r"case|template|extern|using|typedef|static_assert)\b")


def Functions(text: str):
    """(name, first line, lines) of each function defined at namespace or class scope (Google
    style: its signature starts in column 0 or 2, its body closes at the same indent)."""
    lines = text.split("\n")
    out, i = [], 0
    while i < len(lines):
        m = re.match(r"^( {0,2})([A-Za-z_~][\w:<>,~&*\s]*?)\(", lines[i])
        if not m or DECLARATION.match(lines[i].strip()) or "=" in m.group(2):
            i += 1
            continue
        indent, k, opened, depth = m.group(1), i, None, 0
        while k < len(lines) and k < i + 12:  # the signature, to the brace that opens the body
            code = lines[k].split("//")[0].rstrip()
            depth += code.count("(") - code.count(")")
            if depth == 0 and code.endswith("{"):
                opened = k
                break
            if depth == 0 and code.endswith((";", "}")):
                break
            k += 1
        if opened is None:
            i += 1
            continue
        end = opened + 1
        while end < len(lines) and not re.match("^" + indent + r"\}", lines[end]):
            end += 1
        name = re.findall(r"([\w:~]+)\s*\(", m.group(0))
        out.append((name[-1] if name else "?", i + 1, end - i + 1))
        i = end + 1
    return out


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
    long_seen = set()
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
        if not rel.startswith("tests/"):
            for name, first, length in Functions(text):
                key = f"{rel} {name}"
                most = LONG_FUNCTIONS.get(key, MOST_LINES)
                if length > most:
                    bad.append(f"{rel}:{first}: {name} is {length} lines, more than {most} "
                               "(split it: a function fits a screen)")
                    long_seen.add(key)
                elif length > MOST_LINES:
                    long_seen.add(key)
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
    for key in sorted(set(LONG_FUNCTIONS) - long_seen):
        bad.append(f"{key}: no longer over {MOST_LINES} lines; take it off LONG_FUNCTIONS")
    for line in bad:
        print(line)
    print(f"floors: {len(long_seen)} functions over {MOST_LINES} lines remain (issue 52's "
          f"target: none; scripts/floors.py LONG_FUNCTIONS)")
    print(f"floors: {files} files, {len(bad)} problems (an include running up a floor or reaching "
          "the file model, a file or function too long, a Method enumerator named)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
