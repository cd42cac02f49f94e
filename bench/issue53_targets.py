#!/usr/bin/env python3
"""Issue 53's targets measured against a build of fdb02a4 (the issue's baseline), side by side.

    git worktree add /tmp/fdb fdb02a4
    cmake -S /tmp/fdb -B /tmp/fdb/build -DCMAKE_BUILD_TYPE=Release -DNEEDLE_BUILD_TESTS=OFF \
        -DNEEDLE_BUILD_BENCHMARKS=OFF -DNEEDLE_BUILD_PYTHON=OFF
    cmake --build /tmp/fdb/build --target needle
    python3 bench/issue53_targets.py --old /tmp/fdb/build/needle --new build/needle

Each row runs both programs' command lines interleaved, pinned to one core (taskset), and takes
medians. Whole processes, so the start and the case's load are in every time (a few ms): the
ratios they give are lower bounds of the in-process ones. A tolerance sample is the difference
of a study of `--samples` and of 1 sample, over the samples between (the nominal check taken
out). Writes bench/issue53-targets.md.
"""
import argparse
import os
import pathlib
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent


def Timed(cmd, cwd):
    """Wall time of `cmd` and its exit code (0 pass or 1 a failing verdict; else it stops)."""
    t0 = time.perf_counter()
    try:
        r = subprocess.run(cmd, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                           text=True)
    except OSError as e:
        sys.exit("issue53_targets: cannot run %s: %s" % (cmd[0], e))
    t = time.perf_counter() - t0
    if r.returncode not in (0, 1):
        sys.exit("issue53_targets: %s failed (%d): %s" % (" ".join(cmd), r.returncode,
                                                         r.stderr.strip()))
    return t, r.returncode


def Medians(builds, make_cmds, repeats, cwd):
    """Each build's median time of each of `make_cmds` (exe -> command), all runs interleaved;
    stops when the builds' verdicts (exit codes) differ."""
    times = {(name, i): [] for name in builds for i in range(len(make_cmds))}
    for _ in range(repeats):
        for i, make_cmd in enumerate(make_cmds):
            codes = {}
            for name, exe in builds.items():
                t, codes[name] = Timed(make_cmd(exe), cwd)
                times[(name, i)].append(t)
            if len(set(codes.values())) > 1:
                sys.exit("issue53_targets: the builds' verdicts differ on %s: %s"
                         % (" ".join(make_cmd("needle")), codes))
    return {key: statistics.median(t) for key, t in times.items()}


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--old", required=True, help="needle built at fdb02a4")
    p.add_argument("--new", default=str(ROOT / "build" / "needle"))
    p.add_argument("--repeats", type=int, default=9)
    p.add_argument("--samples", type=int, default=41)
    p.add_argument("--out", default=str(ROOT / "bench" / "issue53-targets.md"))
    a = p.parse_args()
    if a.samples < 2:
        sys.exit("issue53_targets: --samples: %d; expected 2 or more" % a.samples)
    builds = {"fdb02a4": os.path.abspath(a.old), "now": os.path.abspath(a.new)}
    pin = ["taskset", "-c", "0"] if shutil.which("taskset") else []
    cases = str(ROOT / "cases")
    out_dir = tempfile.mkdtemp(prefix="needle-issue53-")
    rows = []

    def Row(what, target, make_cmd, per=None):
        m = Medians(builds, [make_cmd] + ([per] if per else []), a.repeats, cases)
        t = {name: m[(name, 0)] for name in builds}
        if per:  # the study of one sample interleaved with the full one, then taken off it
            t = {name: (t[name] - m[(name, 1)]) / (a.samples - 1) for name in builds}
        rows.append((what, t["fdb02a4"], t["now"], target))

    Row("`simulate basu-example1-surge --rpm 520 --dynamic` (the 20-mass chain)", "≥ 10×",
        lambda exe: pin + [exe, "simulate", "basu-example1-surge.toml", "--rpm", "520",
                           "--dynamic", "--json"])
    for name, target in (("basu-example2", "≥ 2.5× (≤ 3 ms)"),
                         ("engine-2000rpm-surging-spring", "≥ 10×")):
        def Study(samples, name=name):
            return lambda exe: pin + [exe, "tolerance", name + ".toml", "--samples",
                                      str(samples), "--seed", "1", "--threads", "1", "--json"]
        Row("a tolerance sample of `%s` (%d − 1 samples)" % (name, a.samples), target,
            Study(a.samples), per=Study(1))
    try:
        Row("`check basu-example1` with its report, one core", "≤ 50 ms",
            lambda exe: pin + [exe, "check", "basu-example1.toml", "--out", out_dir])
    finally:
        shutil.rmtree(out_dir, ignore_errors=True)

    def Ms(seconds):
        return "%.1f" % (seconds * 1e3) if seconds >= 0.01 else "%.2f" % (seconds * 1e3)

    md = ["## Issue 53's targets against fdb02a4's build\n",
          "`python3 bench/issue53_targets.py --old FDB02A4/needle` (whole processes%s, medians of "
          "%d interleaved runs, the two builds' verdicts the same; the start and the case's load "
          "in every time).\n" % (" pinned to one core" if pin else ", not pinned (no taskset)",
                                  a.repeats),
          "| what | fdb02a4 ms | now ms | ratio | target |", "|---|---|---|---|---|"]
    for what, old, new, target in rows:
        md.append("| %s | %s | %s | %.2f× | %s |" % (what, Ms(old), Ms(new), old / new, target))
    pathlib.Path(a.out).write_text("\n".join(md) + "\n")
    print("\n".join(md))


if __name__ == "__main__":
    main()
