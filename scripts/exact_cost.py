"""The cost of method `exact`, counted: instructions (valgrind callgrind, deterministic for one
binary) in one run as `needle simulate` makes it, exact against dopri5 at rtol 1e-8, on the
bench's scenes and the lash scene, and in the overspeed search of Example 2. Writes the table
between the markers of docs/exact.md (--write) or checks it (--check: the same binary and
compiler give the same counts). --before BIN adds a column of another build's counts (the
previous commit's, for the ratio).

  python3 scripts/exact_cost.py --write [--before /path/to/old/needle]
"""
import pathlib
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from doc_block import Block, WriteOrCheck  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent
DOC = ROOT / "docs" / "exact.md"
BEGIN = "<!-- exact-cost: begin (scripts/exact_cost.py --write) -->"
END = "<!-- exact-cost: end -->"

# name, case, rpm (the bench's three scenes, and Example 2's lash-and-ringing speed)
SCENES = [
    ("soft", "basu-cam4-light-spring.toml", 400),
    ("stiff", "basu-cam4-stiff-train.toml", 400),
    ("liftoff", "basu-example2.toml", 1500),
    ("lash", "basu-example2.toml", 1100),
]


def Instructions(command, function):
    """Instructions executed inside `function` (and what it calls) by `command`."""
    with tempfile.TemporaryDirectory() as d:
        out = pathlib.Path(d) / "callgrind.out"
        run = subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=%s" % out,
                              "--toggle-collect=%s" % function] + command,
                             capture_output=True, cwd=ROOT)
        if run.returncode not in (0, 1):  # 1: a run that lifts off (a failing verdict)
            sys.exit("exact_cost.py: %s exited %d: %s"
                     % (" ".join(command), run.returncode, run.stderr.decode()[-500:]))
        summary = subprocess.run(["callgrind_annotate", str(out)], check=True,
                                 capture_output=True, text=True).stdout
    m = re.search(r"^([\d,]+) .*PROGRAM TOTALS", summary, re.M)
    return int(m.group(1).replace(",", ""))


def Run(needle, case, rpm, method):
    return Instructions([needle, "simulate", "cases/" + case, "--rpm", str(rpm), "--method",
                         method, "--rtol", "1e-8", "--dynamic", "--json"], "needle::Integrate*")


def Search(needle):
    return Instructions([needle, "overspeed", "cases/basu-example2.toml", "--from", "600",
                         "--to", "1300", "--threads", "1", "--json"], "needle::OverspeedSearch*")


def M(n):
    return "%.2f M" % (n / 1e6)


def Table(needle, before):
    rows = []
    head = "| scene | rpm | exact | dopri5 rtol 1e-8 | exact / dopri5 |"
    rule = "|---|---|---|---|---|"
    if before:
        head += " exact, previous build | previous / now |"
        rule += "---|---|"
    rows += [head, rule]
    for name, case, rpm in SCENES:
        exact, dopri5 = Run(needle, case, rpm, "exact"), Run(needle, case, rpm, "dopri5")
        row = "| %s (`%s`) | %d | %s | %s | %.3f |" % (name, case, rpm, M(exact), M(dopri5),
                                                         exact / dopri5)
        if before:
            old = Run(before, case, rpm, "exact")
            row += " %s | %.2f× |" % (M(old), old / exact)
        rows.append(row)
    search = Search(needle)
    line = "The overspeed search of Example 2, 600–1300 rpm to 0.5 rpm, one thread: %s" % M(search)
    if before:
        old = Search(before)
        line += " (previous build %s, %.2f×)" % (M(old), old / search)
    return "\n".join(rows) + "\n\n" + line + "."


def main():
    def extra(p):
        p.add_argument("--needle", default=str(ROOT / "build" / "needle"))
        p.add_argument("--before", help="another build's needle binary, for the ratio")
    args = WriteOrCheck(__doc__.splitlines()[0], extra)
    block = Block(DOC, BEGIN, END, "exact_cost.py")
    new = Table(args.needle, args.before)
    if args.write:
        block.Write(new)
    elif block.old.strip() != new.strip():
        sys.exit("exact_cost.py: docs/exact.md's table differs from this build's counts")


if __name__ == "__main__":
    main()
