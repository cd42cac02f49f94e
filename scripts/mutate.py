#!/usr/bin/env python3
"""Mutation testing of the guards: flips each comparison in a source file, one at a time,
rebuilds, runs the tests that guard it, and reports which mutants survive.

  scripts/mutate.py FILE --tests REGEX [--build build] [--target T ...] [--lines A-B] [--max N]
  scripts/mutate.py FILE --tests X --lines A-B --list   (the mutants, nothing built)

A mutant is one operator on one line replaced by its opposite (< ↔ >=, > ↔ <=, == ↔ !=,
&& ↔ ||). It is *killed* when the build fails or a test fails, and *survives* when every test
passes: a comparison no test can tell from its opposite, to be given a test or a written
reason. The file is restored after each mutant (and on Ctrl-C). Exit 0; the score on stdout.
"""
import argparse
import re
import subprocess
import sys

FLIPS = [("<=", ">"), (">=", "<"), ("==", "!="), ("!=", "=="), ("&&", "||"), ("||", "&&"),
         ("<", ">="), (">", "<=")]
# An operator standing alone between operands (not <<, ->, template brackets, #include <…>).
PATTERN = re.compile(r"(?<![<>=!&|-])(<=|>=|==|!=|&&|\|\||<|>)(?![<>=&|])")


def mutants(lines, first, last):
    for n in range(first, min(last, len(lines)) + 1):
        text = lines[n - 1]
        # String literals blanked (a "≥ 13" in a message is not a comparison), then comments.
        code = re.sub(r'"(\\.|[^"\\])*"', lambda q: '"' + " " * (len(q.group()) - 2) + '"', text)
        code = code.split("//")[0]
        if code.lstrip().startswith(("#", "///", "*")) or "template" in code or "<<" in code:
            continue
        for m in PATTERN.finditer(code):
            op = m.group(1)
            if op in "<>" and re.search(r"\w<|>\s*[&*\w(]", code[max(0, m.start() - 1):m.end() + 2]):
                if not re.search(r"\s[<>]\s", code[max(0, m.start() - 1):m.end() + 1]):
                    continue  # a template argument list, not a comparison
            new = dict(FLIPS)[op]
            yield n, m.start(), op, new


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("file")
    ap.add_argument("--tests", required=True, help="ctest -R regex of the guarding tests")
    ap.add_argument("--build", default="build")
    ap.add_argument("--target", action="append", default=[])
    ap.add_argument("--lines", default="1-1000000")
    ap.add_argument("--max", type=int, default=1000)
    ap.add_argument("--list", action="store_true", help="list the mutants, build nothing")
    a = ap.parse_args()
    first, last = map(int, a.lines.split("-"))
    original = open(a.file).read()
    lines = original.split("\n")
    if a.list:
        for n, col, op, new in mutants(lines, first, last):
            print(f"{a.file}:{n}: {op} -> {new}: {lines[n - 1].strip()}")
        return 0
    killed, survived = 0, []
    try:
        for k, (n, col, op, new) in enumerate(mutants(lines, first, last)):
            if k >= a.max:
                break
            text = lines[n - 1]
            mutated = lines[:]
            mutated[n - 1] = text[:col] + new + text[col + len(op):]
            open(a.file, "w").write("\n".join(mutated))
            build = ["cmake", "--build", a.build, "-j2"] + sum((["--target", t] for t in a.target), [])
            ok = subprocess.run(build, capture_output=True).returncode == 0
            if ok:
                ok = subprocess.run(["ctest", "--test-dir", a.build, "-R", a.tests, "-j2"],
                                    capture_output=True).returncode == 0
            where = f"{a.file}:{n}: {op} -> {new}: {text.strip()}"
            if ok:
                survived.append(where)
                print("SURVIVED", where, flush=True)
            else:
                killed += 1
                print("killed  ", where, flush=True)
    finally:
        open(a.file, "w").write(original)
        subprocess.run(["cmake", "--build", a.build, "-j2"] +
                       sum((["--target", t] for t in a.target), []), capture_output=True)
    total = killed + len(survived)
    print(f"mutation score: {killed}/{total} killed" + (f" ({100 * killed / total:.0f} %)" if total else ""))
    for s in survived:
        print("  survivor:", s)


if __name__ == "__main__":
    sys.exit(main())
