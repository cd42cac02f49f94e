#!/usr/bin/env python3
"""Random rise-dwell-return laws exported as users export them: refusals, misreadings, bands.

Each trial table joins a rise and a return drawn from eight kinds of law (harmonic, double
harmonic, cycloidal, 3-4-5, 4-5-6-7, modified trapezoid, modified sine, and a random law whose
s'' is piecewise linear between six random knots, which may jump at the seat and at the top),
with or without a dwell, of 0.3-15 mm, over 8-120 deg crank each (8-30 deg on the 30 % of sparse
tables), exported every 0.25-3 deg to 9 decimals, 1e-4 or 1e-3 mm, from the rise's first point
or with 1-10 readings of base circle (the grid then off the rise by 0, 1/4, 1/3, 1/2 or 0.7 of a
step), in crank or cam degrees. (A fresh-context helper wrote the generator as an outside
trial; it is kept here so that its figures can be regenerated.) The truth is the closed form's
largest and smallest s'' at 1000 rpm; `needle kinematics FILE.csv --rpm 1000 --json` reads each
table with no settings.

    python3 bench/export_trial.py [--needle BIN ...] [--tables 600] [--seed 1] [--out FILE.md]

prints, for each binary, the tables refused (or over 600 s) and read as measured (every table is
an exact export: both are misreadings), and the extremes whose truth lies beyond their band's
unsafe end (a_max above the band, a_min below it: a verdict judged there passes what it should
fail), by sparse (under 30 readings) and dense tables, and by how many steps the narrower of the
rise and the return spans. Needs NumPy and SciPy (Debian python3-numpy, python3-scipy).
"""
import argparse
import collections
import json
import math
import os
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

from debian_python import reexec_or_exit

try:
    import numpy as np
    from scipy.integrate import quad
except ImportError:
    reexec_or_exit(__file__, "export_trial.py: needs NumPy and SciPy "
                   "(Debian: apt-get install python3-scipy)")

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PI = math.pi
LAWS = ["harmonic", "dharmonic", "cycloidal", "345", "4567", "modtrap", "modsine", "cspline"]


def law_accel(name, rng):
    """The law's s'' shape a(x) on 0..1 and its breakpoints."""
    if name == "harmonic":
        return (lambda x: math.cos(PI * x)), []
    if name == "dharmonic":
        return (lambda x: math.cos(PI * x) - math.cos(2 * PI * x)), []
    if name == "cycloidal":
        return (lambda x: math.sin(2 * PI * x)), []
    if name == "345":
        return (lambda x: 60 * x - 180 * x**2 + 120 * x**3), []
    if name == "4567":
        return (lambda x: 420 * x**2 - 1680 * x**3 + 2100 * x**4 - 840 * x**5), []
    if name == "modtrap":
        def a(x):
            if x <= 1 / 8:
                return math.sin(4 * PI * x)
            if x <= 3 / 8:
                return 1.0
            if x <= 5 / 8:
                return math.cos(4 * PI * (x - 3 / 8))
            if x <= 7 / 8:
                return -1.0
            return -math.cos(4 * PI * (x - 7 / 8))
        return a, [1 / 8, 3 / 8, 5 / 8, 7 / 8]
    if name == "modsine":
        def a(x):
            if x <= 1 / 8:
                return math.sin(4 * PI * x)
            if x <= 7 / 8:
                return math.cos(4 * PI / 3 * (x - 1 / 8))
            return -math.cos(4 * PI * (x - 7 / 8))
        return a, [1 / 8, 7 / 8]
    # cspline: a positive lobe on [0, c], a negative one on [c, 1], s'' linear between knots.
    c = rng.uniform(0.3, 0.65)
    a0 = rng.choice([0.0, 0.0, rng.uniform(0.2, 1.0)])  # a jump off the seat, sometimes
    p1, p2 = sorted(rng.uniform(0.05, 0.95, 2) * c)
    v1, v2 = rng.uniform(0.5, 1.0), rng.uniform(0.3, 1.0)
    q1, q2 = sorted(c + rng.uniform(0.05, 0.95, 2) * (1 - c))
    w1, w2 = rng.uniform(0.3, 1.0), rng.uniform(0.3, 1.0)
    a1 = rng.choice([0.0, 0.0, rng.uniform(0.2, 1.0)])  # a jump at the top, sometimes
    posx, posv = [0, p1, p2, c], [a0, v1, v2, 0]
    negx, negv = [c, q1, q2, 1], [0, -w1, -w2, -a1]
    def area(x, v):  # the trapezoid rule: exact for s'' linear between knots
        return sum(0.5 * (v[k] + v[k + 1]) * (x[k + 1] - x[k]) for k in range(len(x) - 1))
    scale = -area(posx, posv) / area(negx, negv)  # the velocity back to 0 at the top
    knots = np.array([0, p1, p2, c, q1, q2, 1], float)
    values = np.array(posv + [v * scale for v in negv[1:]], float)
    return (lambda x: float(np.interp(x, knots, values))), list(knots[1:-1])


class Rise:
    """s(x)/h on 0..1 from its s'' shape: the double integral, normalised to reach 1."""

    def __init__(self, a, breaks):
        self.a, self.breaks = a, breaks
        self.norm = self._integral(1.0)

    def _integral(self, x):
        pts = [p for p in self.breaks if 0 < p < x]
        return quad(lambda t: (x - t) * self.a(t), 0, x, points=pts or None, limit=200,
                    epsabs=1e-16, epsrel=1e-14)[0]

    def f(self, x):
        return 0.0 if x <= 0 else 1.0 if x >= 1 else self._integral(x) / self.norm

    def extremes(self, lift_m, beta_rad):
        """The least and largest s'' (m/rad²), the breakpoints' one-sided values included."""
        x = np.linspace(0, 1, 20001)
        b = np.array(self.breaks, float)
        x = np.unique(np.concatenate([x, np.clip(b - 1e-12, 0, 1), np.clip(b + 1e-12, 0, 1)]))
        a = np.array([self.a(t) for t in x]) / self.norm * lift_m / beta_rad**2
        return a.min(), a.max()


def random_table(i, rng):
    """One table: (name, csv text, record) or None when it is out of 10-2000 rows."""
    sparse = rng.random() < 0.3
    if sparse:
        step = float(rng.choice([1.5, 2.0, 2.5, 3.0]))
        br = float(rng.uniform(8, 30))
        bd = br if rng.random() < 0.4 else float(rng.uniform(8, 30))
        d = float(rng.choice([0, 0, rng.uniform(0, 10)]))
    else:
        step = float(rng.choice([0.25, 0.3, 0.5, 0.7, 0.75, 1.0, 1.25, 1.5, 2.0, 2.5, 3.0]))
        br = float(rng.uniform(8, 120))
        bd = br if rng.random() < 0.4 else float(rng.uniform(8, 120))
        d = float(rng.choice([0, 0, rng.uniform(0, 40)]))
    h = float(np.exp(rng.uniform(np.log(0.3), np.log(15))))
    pad = int(rng.choice([0, 0, rng.integers(1, 11)]))
    offset = 0.0 if pad == 0 or rng.random() < 0.5 else float(rng.choice([0.25, 0.5, 1 / 3, 0.7]))
    if pad == 0:  # the whole a multiple of the step: the return stretched
        n = max(2, round((br + d + bd) / step))
        bd = n * step - br - d
        if bd < 4:
            bd += step * math.ceil((8 - bd) / step)
    if rng.random() < 0.3:  # whole degrees, sometimes (junctions on a grid of whole steps)
        br, bd, d = round(br), round(bd), round(d)
        if pad == 0:
            bd += step * round((br + d + bd) / step) - (br + d + bd)
    prec = int(rng.choice([9, 4, 3]))
    col = "cam_deg" if rng.random() < 0.2 else "crank_deg"
    rise_kind = str(rng.choice(LAWS))
    return_kind = rise_kind if rng.random() < 0.6 else str(rng.choice(LAWS))
    rise, ret = Rise(*law_accel(rise_kind, rng)), Rise(*law_accel(return_kind, rng))
    end = br + d + bd

    def s(th):
        if th <= 0 or th >= end:
            return 0.0
        if th <= br:
            return h * rise.f(th / br)
        if th <= br + d:
            return h
        return h * ret.f((end - th) / bd)

    th0, th1 = (0.0, end) if pad == 0 else (-pad * step + offset * step, end + pad * step)
    n = int(math.floor((th1 - th0) / step + 1e-9)) + 1
    if n > 2000 or n < 10:
        return None
    lines = [f"{col},lift_mm"]
    for k in range(n):
        th = th0 + k * step
        angle = round(th / 2, 6) if col == "cam_deg" else round(th, 6)
        text = ("%.6f" % angle).rstrip("0").rstrip(".")
        lines.append("%s,%s" % ("0" if text in ("-0", "") else text,
                                "%.*f" % (prec, s(2 * angle if col == "cam_deg" else angle))))
    w2 = (2 * PI * 1000.0 / 60) ** 2
    lows, highs = zip(rise.extremes(h * 1e-3, math.radians(br)),
                      ret.extremes(h * 1e-3, math.radians(bd)))
    record = dict(rise=rise_kind, ret=return_kind, rows=n, step=step, prec=prec, col=col,
                  steps=min(br, bd) / step, amax=max(max(highs), 0.0) * w2,
                  amin=min(min(lows), 0.0) * w2)
    return "E%04d" % i, "\n".join(lines) + "\n", record


def read(binary, path, record):
    args = [binary, "kinematics", path, "--rpm", "1000", "--json"]
    if record["col"] == "cam_deg":
        args += ["--cycle", "four-stroke"]
    try:
        p = subprocess.run(args, capture_output=True, text=True, timeout=600)
    except subprocess.TimeoutExpired:
        return None  # counted with the refusals
    return json.loads(p.stdout) if p.returncode == 0 else None


def classes(record):
    s = record["steps"]
    return ("sparse" if record["rows"] < 30 else "dense",
            "under 4" if s < 4 else "4-12" if s < 12 else "12 or more")


def summary(binary, tables, jobs, misread):
    with ThreadPoolExecutor(jobs) as ex:
        results = list(ex.map(lambda t: read(binary, t[1], t[2]), tables))
    count = collections.Counter()
    for (name, path, rec), j in zip(tables, results):
        if j is None or j.get("measured"):
            misread.append(f"{binary}: {name} ({rec['rise']}, {rec['ret']}, {rec['rows']} rows "
                           f"every {rec['step']} deg, {rec['prec']} decimals) "
                           + ("refused" if j is None else "read as measured"))
        if j is None:
            count["refused"] += 1
            continue
        count["measured"] += bool(j.get("measured"))
        for key, truth, sign in (("max", rec["amax"], 1), ("min", rec["amin"], -1)):
            band = j.get(f"{key}_acceleration_band_m_s2")
            if band is None:  # no band to judge: counted apart, not as held
                count["no band"] += 1
                continue
            beyond = sign * (truth - (band[1] if sign > 0 else band[0])) > 0
            for c in ("all",) + classes(rec):
                count[("extremes", c)] += 1
                count[("beyond", c)] += beyond
    return count


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--needle", action="append",
                    help="a needle binary, or LABEL=BINARY (repeat to compare)")
    ap.add_argument("--tables", type=int, default=600, help="random tables")
    ap.add_argument("--seed", type=int, default=1, help="the tables' random seed")
    ap.add_argument("--jobs", type=int, default=2, help="needle processes at a time")
    ap.add_argument("--out", help="also write the summary to this Markdown file")
    ap.add_argument("--keep", help="write the tables to this directory too")
    a = ap.parse_args()
    binaries = a.needle or [os.path.join(ROOT, "build", "needle")]
    rng = np.random.default_rng(a.seed)
    with tempfile.TemporaryDirectory() as work:
        tables, i = [], 0
        while len(tables) < a.tables:
            t = random_table(i, rng)
            i += 1
            if t:
                path = os.path.join(work, t[0] + ".csv")
                with open(path, "w") as f:
                    f.write(t[1])
                tables.append((t[0], path, t[2]))
        sparse = sum(1 for t in tables if t[2]["rows"] < 30)
        cols = ["all", "sparse", "dense", "under 4", "4-12", "12 or more"]
        out = [f"{len(tables)} random exact exports (seed {a.seed}; {sparse} sparse), "
               "`needle kinematics --rpm 1000 --json` with no settings. Truth beyond the "
               "unsafe end of its band, of the extremes (a_max and a_min of each table read), by "
               "table and by the steps the narrower of the rise and the return spans:", "",
               "| binary | refused | read as measured | extremes without a band | "
               + " | ".join(cols) + " |",
               "|---|---|---|---|" + "---|" * len(cols)]
        if a.keep:
            os.makedirs(a.keep, exist_ok=True)
            for name, path, _ in tables:
                with open(path) as f, open(os.path.join(a.keep, name + ".csv"), "w") as g:
                    g.write(f.read())
        misread = []
        for given in binaries:
            label, b = given.split("=", 1) if "=" in given else (given, given)
            c = summary(b, tables, a.jobs, misread)
            cells = []
            for k in cols:
                n, m = c[("extremes", k)], c[("beyond", k)]
                cells.append(f"{m}/{n} ({100.0 * m / n:.1f} %)" if n else "-")
            out.append(f"| {label} | {c['refused']} | {c['measured']} | {c['no band']} | "
                       + " | ".join(cells) + " |")
    print("\n".join(out + [""] + misread))
    if a.out:
        with open(a.out, "w") as f:
            f.write("\n".join(out) + "\n")


if __name__ == "__main__":
    sys.exit(main())
