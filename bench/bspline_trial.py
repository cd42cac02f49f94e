#!/usr/bin/env python3
"""Random cubic B-spline cams as users export them: how often needle's band leaves out the truth.

A cubic B-spline cam (a CAD export's law) has s'' piecewise linear between its knots and its
peaks at knots: V-tops that the local fit's windows round off. Each trial law has 9 knots
symmetric about mid-rise (three drawn at random in each half, at least 0.03 of the rise apart),
s'' through the cycloidal's at each (bench/lift_tables.py bspline_profile), a rise and a return
of 20-120 deg crank, a dwell of none or up to 10 deg, a lift of 0.3-10 mm, and is exported every
0.25, 0.5, 1 or 1.5 deg to 9 decimals, 1e-4 or 1e-3 mm, with or without 10 deg of base circle.
`needle kinematics --json` reads each with no settings; the closed form gives the truth.

    python3 bench/bspline_trial.py [--needle BIN] [--laws 200] [--seed 7]

prints the extremes whose truth lies beyond the band's unsafe end (a_max above its band, a_min
below its band: a verdict judged there passes what it should fail), and those that miss the
issue's targets (within 1 %, 2 %, 5 % by export, or the truth inside a band no wider than twice
that), overall and by export. Needs NumPy (and SciPy for bench/lift_tables.py's import).
"""
import argparse
import os
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import lift_tables as L  # noqa: E402


def random_law(rng, i):
    while True:
        inner = np.sort(0.02 + 0.46 * rng.random(3))
        knots = np.concatenate(([0.0], inner, [0.5]))
        if np.all(np.diff(knots) >= 0.03):
            break
    t = np.concatenate((knots, 1.0 - knots[-2::-1]))
    rise, ret = 20 + 100 * rng.random(), 20 + 100 * rng.random()
    lift = 0.3 + 9.7 * rng.random()
    dwell = 0.0 if rng.random() < 0.5 else 10 * rng.random()
    law = L.Law(key=f"bspline{i}", title="random cubic B-spline", angle="crank", rpm=1000.0,
                mass_kg=0.1, preload_N=100.0, rate_N_mm=10.0, rise_deg=rise,
                pieces=L.rise_dwell_return(L.bspline_profile(t), lift, 0.0, rise, dwell, ret))
    law.truth = L.closed_form_truth(law)
    kind = ("exact9", "r1e-4", "r1e-3")[rng.integers(3)]
    table = L.Table(law.key, kind, step=(0.25, 0.5, 1.0, 1.5)[rng.integers(4)],
                    pad=bool(rng.integers(2)))
    return law, table


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--needle", default=os.path.join(L.ROOT, "build", "needle"), help="the needle binary")
    ap.add_argument("--laws", type=int, default=200, help="random laws, one table each")
    ap.add_argument("--seed", type=int, default=7, help="the laws' random seed")
    a = ap.parse_args()
    rng = np.random.default_rng(a.seed)
    counts = {}
    with tempfile.TemporaryDirectory() as work:
        for i in range(a.laws):
            law, t = random_law(rng, i)
            _, _, text = L.table_data(law, t)
            path = os.path.join(work, t.name + ".csv")
            with open(path, "w") as f:
                f.write(text)
            j, err, _ = L.run_needle(a.needle, ["kinematics", path, "--rpm", f"{law.rpm:g}", "--json"])
            c = counts.setdefault(t.kind, [0, 0, 0, 0])    # extremes, beyond, missed, failed
            tol = L.EXPORTS[t.kind][2]
            for key, sign in (("max", 1.0), ("min", -1.0)):
                c[0] += 1
                value = L._number(j, f"{key}_acceleration_m_s2")
                band = L._band(j, f"{key}_acceleration_band_m_s2")
                truth = law.truth[f"a_{key}"]
                if err or value is None or band is None:
                    c[3] += 1
                    continue
                unsafe_end = band[1] if sign > 0 else band[0]
                c[1] += sign * (truth - unsafe_end) > 0
                c[2] += not L.judge(value, band, truth, tol)
    total = [sum(c[k] for c in counts.values()) for k in range(4)]
    print(f"bspline_trial: {a.laws} laws, seed {a.seed}, {a.needle}")
    for kind, c in sorted(counts.items()) + [("all", total)]:
        print(f"  {kind:7s} extremes {c[0]:4d}  truth beyond the unsafe end {c[1]:4d}  "
              f"targets missed {c[2]:4d}  not read {c[3]}")


if __name__ == "__main__":
    main()
