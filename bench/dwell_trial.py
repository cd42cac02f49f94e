#!/usr/bin/env python3
"""Harmonic rise, short dwell, harmonic return: how needle reads the junctions beside a dwell.

Each trial law is a harmonic (simple harmonic motion) rise over R, a dwell of D and a harmonic
return over T crank degrees (R, T drawn in 30-80 deg, D in 2-25 deg, lift 1-10 mm), exported from
the rise's first point every 0.25, 0.5, 1 or 2 deg to 9 decimals, 1e-4 or 1e-3 mm. A short dwell
puts few readings between two s'' jumps, and the junctions found beside it may be a reading or
two off (lib/lift_dwells.cc SeekDwells, lib/lift_pieces.cc PieceTrim). The truth: a_max = -a_min
= (H/2)(pi/min(R, T))^2 omega^2 at 1000 rpm. `needle kinematics FILE.csv --rpm 1000 --json` reads
each table with no settings.

    python3 bench/dwell_trial.py --needle LABEL=BIN [--needle ...] [--tables 250] [--seed 21]

prints, for each binary, the tables that miss the issue's target (an extreme within 1 %, 2 % or
5 % by export, or the truth inside its band), and each table that the binaries read differently.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

from debian_python import reexec_or_exit

try:
    import numpy as np
except ImportError:
    reexec_or_exit(__file__, "dwell_trial.py: needs NumPy (Debian: apt-get install python3-numpy)")

TOLERANCE = {9: 0.01, 4: 0.02, 3: 0.05}  # decimals printed -> the target


def lift_mm(theta, rise, dwell, ret, height):
    s = np.zeros_like(theta)
    up = (theta >= 0) & (theta <= rise)
    s[up] = height / 2 * (1 - np.cos(np.pi * theta[up] / rise))
    s[(theta > rise) & (theta <= rise + dwell)] = height
    down = (theta > rise + dwell) & (theta <= rise + dwell + ret)
    s[down] = height / 2 * (1 + np.cos(np.pi * (theta[down] - rise - dwell) / ret))
    return s


def read(needle, path):
    out = subprocess.run([needle, "kinematics", path, "--rpm", "1000", "--json"],
                         capture_output=True, text=True)
    return json.loads(out.stdout) if out.returncode == 0 else None


def judge(j, truth, tol):
    """Whether both extremes meet the target: within tol, or the truth inside the band."""
    if j is None:
        return False
    for key, want in (("max", truth), ("min", -truth)):
        lo, hi = j[f"{key}_acceleration_band_m_s2"]
        if not (abs(j[f"{key}_acceleration_m_s2"] / want - 1) <= tol or lo <= want <= hi):
            return False
    return True


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--needle", action="append", required=True, help="LABEL=BINARY (repeat)")
    ap.add_argument("--tables", type=int, default=250, help="random tables")
    ap.add_argument("--seed", type=int, default=21, help="the tables' random seed")
    a = ap.parse_args()
    bins = [n.split("=", 1) if "=" in n else (n, n) for n in a.needle]
    rng = np.random.default_rng(a.seed)
    omega = 2 * np.pi * 1000 / 60
    missed = {label: 0 for label, _ in bins}
    with tempfile.TemporaryDirectory() as work:
        path = os.path.join(work, "table.csv")
        for k in range(a.tables):
            rise, dwell, ret = rng.uniform(30, 80), rng.uniform(2, 25), rng.uniform(30, 80)
            height = rng.uniform(1, 10)
            decimals = int(rng.choice([9, 4, 3]))
            step = float(rng.choice([0.25, 0.5, 1.0, 2.0]))
            theta = np.arange(0.0, rise + dwell + ret + 1e-9, step)
            with open(path, "w") as f:
                f.write("crank_deg,lift_mm\n")
                for t, s in zip(theta, lift_mm(theta, rise, dwell, ret, height)):
                    f.write(f"{t:.6f},{round(s, decimals):.{decimals}f}\n")
            truth = height * 1e-3 / 2 * (np.pi / np.radians(min(rise, ret))) ** 2 * omega**2
            seen = []
            for label, needle in bins:
                j = read(needle, path)
                ok = judge(j, truth, TOLERANCE[decimals])
                missed[label] += not ok
                seen.append("refused" if j is None else
                            f"{'met' if ok else 'MISSED'} a_max {j['max_acceleration_m_s2']:.1f} "
                            f"a_min {j['min_acceleration_m_s2']:.1f}")
            if len(set(seen)) > 1:
                print(f"table {k}: R {rise:.3f}, D {dwell:.3f}, T {ret:.3f} deg, H {height:.3f} mm, "
                      f"every {step:g} deg to {decimals} decimals, truth +-{truth:.1f} m/s^2: "
                      + "; ".join(f"{label} {s}" for (label, _), s in zip(bins, seen)))
    for label, _ in bins:
        print(f"dwell_trial: {label}: {missed[label]} of {a.tables} tables miss the target "
              f"(seed {a.seed})")


if __name__ == "__main__":
    sys.exit(main())
