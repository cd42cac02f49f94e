#!/usr/bin/env python3
"""Harmonic rise, short dwell, harmonic return: how needle reads the junctions beside a dwell.

Each trial law is a harmonic (simple harmonic motion) rise over R, a dwell of D and a harmonic
return over T crank degrees (R, T drawn in 30-80 deg, D in 2-25 deg, lift 1-10 mm), exported from
the rise's first point to the first reading on the seat after the return, every 0.25, 0.5, 1 or
2 deg to 9 decimals, 1e-4 or 1e-3 mm
(bench/lift_tables.py's laws, exports and judge). A short dwell puts few readings between two
s'' jumps, and the junctions found beside it may be a reading or two off (lib/lift_dwells.cc
SeekDwells, lib/lift_pieces.cc PieceTrim). `needle kinematics FILE.csv --rpm 1000 --json` reads
each table with no settings; the closed form gives the truth.

    python3 bench/dwell_trial.py --needle LABEL=BIN [--needle ...] [--tables 2000] [--seed 21]

prints, for each binary, the tables that miss the issue's target on a_max or a_min (within 1 %,
2 % or 5 % by export, or the truth inside a band no wider than twice that) and the extremes whose
truth lies beyond their band's unsafe end (a verdict judged there passes what it should fail),
and each table that the binaries judge differently. Needs NumPy (and SciPy for bench/lift_tables.py's import).
"""
import argparse
import os
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import lift_tables as L  # noqa: E402


def random_table(rng, k):
    rise, dwell, ret = rng.uniform(30, 80), rng.uniform(2, 25), rng.uniform(30, 80)
    lift = rng.uniform(1, 10)
    law = L.Law(key=f"dwell{k}", title="harmonic rise, dwell, harmonic return", angle="crank",
                rpm=1000.0, mass_kg=0.1, preload_N=100.0, rate_N_mm=10.0, rise_deg=rise,
                pieces=L.rise_dwell_return(L.shm, lift, 0.0, rise, dwell, ret))
    law.truth = L.closed_form_truth(law)
    table = L.Table(law.key, ("exact9", "r1e-4", "r1e-3")[rng.integers(3)],
                    step=(0.25, 0.5, 1.0, 2.0)[rng.integers(4)], pad=False, to_seat=True)
    return law, table, f"R {rise:.3f}, D {dwell:.3f}, T {ret:.3f} deg, H {lift:.3f} mm"


def verdict(binary, path, law, kind):
    """Whether both extremes meet the target, how many have their truth beyond the band's
    unsafe end (a_max above it, a_min below it), and 'met' or 'MISSED' with the extremes read."""
    j, err, _ = L.run_needle(binary, ["kinematics", path, "--rpm", f"{law.rpm:g}", "--json"])
    if err:
        return False, 0, err
    met, beyond, text = True, 0, []
    for key, sign in (("max", 1.0), ("min", -1.0)):
        value = L._number(j, f"{key}_acceleration_m_s2")
        band = L._band(j, f"{key}_acceleration_band_m_s2")
        truth = law.truth[f"a_{key}"]
        met &= L.judge(value, band, truth, L.EXPORTS[kind][2])
        beyond += bool(band) and sign * (truth - (band[1] if sign > 0 else band[0])) > 0
        text.append(f"a_{key} " + ("none" if value is None else f"{value:.1f}"))
    return met, beyond, ("met " if met else "MISSED ") + " ".join(text)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--needle", action="append", required=True, help="LABEL=BINARY (repeat)")
    ap.add_argument("--tables", type=int, default=2000, help="random tables")
    ap.add_argument("--seed", type=int, default=21, help="the tables' random seed")
    a = ap.parse_args()
    bins = [n.split("=", 1) if "=" in n else (n, n) for n in a.needle]
    rng = np.random.default_rng(a.seed)
    missed = {label: 0 for label, _ in bins}
    beyond = {label: 0 for label, _ in bins}
    with tempfile.TemporaryDirectory() as work:
        path = os.path.join(work, "table.csv")
        for k in range(a.tables):
            law, t, what = random_table(rng, k)
            with open(path, "w") as f:
                f.write(L.table_data(law, t)[2])
            seen = []
            for label, binary in bins:
                met, out, text = verdict(binary, path, law, t.kind)
                missed[label] += not met
                beyond[label] += out
                seen.append(text)
            if len({s.split()[0] for s in seen}) > 1:
                print(f"table {k}: {what}, every {t.step:g} deg, {t.kind}, truth "
                      f"{law.truth['a_max']:.1f} / {law.truth['a_min']:.1f} m/s^2: "
                      + "; ".join(f"{label} {s}" for (label, _), s in zip(bins, seen)))
    for label, _ in bins:
        print(f"dwell_trial: {label}: {missed[label]} of {a.tables} tables miss the target, "
              f"{beyond[label]} of {2 * a.tables} extremes lie beyond their band's unsafe end "
              f"(seed {a.seed})")


if __name__ == "__main__":
    sys.exit(main())
