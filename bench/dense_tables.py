#!/usr/bin/env python3
"""Dense lift tables: needle's wall time on tables of 1e6 rows, two binaries side by side.

    python3 bench/dense_tables.py [--needle PATH] [--before PATH] [--repeats N] [--out DIR]

Writes three tables of 1,000,001 readings of a cycloidal rise and return (10 mm over 120° and
120° of crank) to a temporary directory:

  * `staircase.csv`: angles to 1e-6°, lifts rounded to 1e-4 mm (an encoder's staircase);
  * `exact.csv`: the same angles, lifts to 9 decimals (an exact export);
  * `measured.csv`: the lifts with 1 µm of Gaussian noise, to 1e-6 mm (an encoder's trace);
  * `array.toml`: a case whose `[lift]` holds the staircase as `crank_deg` and `lift_mm`
    arrays of 1e6 elements each.

and runs `needle kinematics FILE --rpm 300 --json` (the case: `needle kinematics FILE --json`)
on each, alternating the two binaries, `--repeats` times (default 5). Reports the median wall
time of each and their ratio, and needle's a_max against the closed form (14.137 m/s²) with
its band. Writes DIR/dense-tables.md (default bench/). Needs NumPy (Debian: python3-numpy).
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

from debian_python import reexec_or_exit

try:
    import numpy as np
except ImportError:
    reexec_or_exit(__file__, "dense_tables.py: needs NumPy (apt-get install python3-numpy)")

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ROWS = 1_000_001
RPM = 300.0


def cycloid(theta):
    """10 mm cycloidal rise over 0–120°, return over 120–240° (crank degrees)."""
    def c(x, b):
        return x / b - np.sin(2 * np.pi * x / b) / (2 * np.pi)
    return np.where(theta <= 120.0, 10.0 * c(theta, 120.0), 10.0 * (1.0 - c(theta - 120.0, 120.0)))


def truth_a_max():
    """2π h / β² in mm/deg², times ω² in deg²/s², in m/s²."""
    omega = RPM * 360.0 / 60.0
    return 2 * math.pi * 10.0 / 120.0 ** 2 * omega ** 2 * 1e-3


def write_tables(d):
    theta = np.linspace(0.0, 240.0, ROWS)
    s = cycloid(theta)
    files = {}
    noisy = s + np.random.default_rng(477).normal(0.0, 1e-3, s.size)
    for name, lift, fmt in [("staircase", np.round(s, 4), "%.4f"), ("exact", s, "%.9f"),
                            ("measured", noisy, "%.6f")]:
        path = os.path.join(d, name + ".csv")
        with open(path, "w") as f:
            f.write("crank_deg,lift_mm\n")
            np.savetxt(f, np.column_stack([theta, lift]), fmt=["%.6f", fmt], delimiter=",")
        files[name] = [path, "--rpm", str(RPM)]
    path = os.path.join(d, "array.toml")
    with open(path, "w") as f:
        f.write('title = "1e6-element lift arrays"\n[engine]\nspeed_rpm = %g\ncycle = "two-stroke"\n'
                "[lift]\ncrank_deg = [" % RPM)
        f.write(",".join("%.6f" % t for t in theta))
        f.write("]\nlift_mm = [")
        f.write(",".join("%.4f" % v for v in np.round(s, 4)))
        f.write("]\n")
    files["array"] = [path]
    return files


def run(binary, args):
    t0 = time.perf_counter()
    p = subprocess.run([binary, "kinematics"] + args + ["--json"], capture_output=True, text=True)
    wall = time.perf_counter() - t0
    j = json.loads(p.stdout) if p.returncode == 0 else None
    return wall, j, (p.stderr.strip().splitlines() or [""])[-1]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--needle", default=os.path.join(ROOT, "build", "needle"))
    ap.add_argument("--before", help="a binary to time beside it (the build before a change)")
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--out", default=os.path.join(ROOT, "bench"))
    a = ap.parse_args()
    binaries = [("needle", a.needle)] + ([("before", a.before)] if a.before else [])
    truth = truth_a_max()
    lines = ["## Dense lift tables: 1e6 rows", "",
             f"`needle kinematics` wall time on 1,000,001 readings of a cycloidal rise and return "
             f"(10 mm over 120° + 120° of crank, {RPM:g} rpm; a_max = {truth:.3f} m/s²), median of "
             f"{a.repeats} runs alternating the binaries, one process at a time. Regenerate with "
             "`python3 bench/dense_tables.py [--before OLD]`. Target (issue 50): ≤ 1 s.", "",
             "| table | " + " | ".join(f"{n} s" for n, _ in binaries) +
             (" | before / needle" if a.before else "") + " | a_max m/s² | band | reading |" +
             (" before: a_max |" if a.before else ""),
             "|---|" + "---|" * (len(binaries) + (2 if a.before else 0) + 3)]
    with tempfile.TemporaryDirectory() as d:
        files = write_tables(d)
        labels = {"staircase": "CSV, lifts rounded to 1e-4 mm (a staircase)",
                  "exact": "CSV, lifts to 9 decimals (an exact export)",
                  "measured": "CSV, 1 µm of noise (a measured trace)",
                  "array": "case file, 1e6-element `lift_mm` array (staircase)"}
        for name, args in files.items():
            times = {n: [] for n, _ in binaries}
            last = None
            before_amax = ""
            for _ in range(a.repeats):
                for n, b in binaries:
                    wall, j, err = run(b, args)
                    times[n].append(wall)
                    if n == "needle":
                        last = j if j else err
                    elif j:
                        before_amax = f"{j['max_acceleration_m_s2']:.3f}"
                    else:
                        before_amax = "failed"
            med = {n: statistics.median(v) for n, v in times.items()}
            if isinstance(last, dict):
                band = last.get("max_acceleration_band_m_s2")
                amax = f"{last['max_acceleration_m_s2']:.3f}"
                band_s = f"[{band[0]:.3f}, {band[1]:.3f}]" if band else "none"
                reading = last.get("spline", "")
            else:
                amax, band_s, reading = "failed", "", str(last)
            row = f"| {labels[name]} | " + " | ".join(f"{med[n]:.2f}" for n, _ in binaries)
            if a.before:
                row += f" | {med['before'] / med['needle']:.2f}×"
            row += f" | {amax} | {band_s} | {reading} |"
            lines.append(row + (f" {before_amax} |" if a.before else ""))
            print(lines[-1], flush=True)
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, "dense-tables.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
