"""needle from Python: Basu's Example 1 loaded, its lift, velocity, acceleration and jerk (SVAJ)
plotted when matplotlib is there, one dynamic run, an overspeed sweep, and the case changed and
checked again.

    cmake --build build && PYTHONPATH=build/python python3 docs/python_example.py [OUT.png]

Every function returns what `needle COMMAND --json` prints, as a dict (the keys name their
units), with the command's table as NumPy arrays in SI under "columns" and the command's exit
status under "exit_status"; bad input raises needle.CaseError naming the case's key or the
keyword. A case is a path, a dict of the file's sections, or a needle.Case, which reads and
writes like that dict.
"""
import os
import sys

import numpy as np

import needle

here = os.path.dirname(os.path.abspath(__file__))
case = needle.load_case(os.path.join(here, "..", "cases", "basu-example1.toml"))

kin = needle.kinematics(case, step_deg=0.5)
c = kin["columns"]
print(f"{case.title}: max lift {kin['max_lift_mm']:.3f} mm at {kin['max_lift_deg']:.1f} deg, "
      f"max velocity {kin['max_velocity_m_s']:.3f} m/s, spline {kin['spline']}")

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    plt = None
if plt is not None:
    deg = np.degrees(c["crank_rad"])
    fig, axes = plt.subplots(4, 1, sharex=True, figsize=(7, 9))
    for ax, key, label in zip(axes, ["lift_m", "velocity_m_s", "acceleration_m_s2", "jerk_m_s3"],
                              ["lift, mm", "velocity, m/s", "acceleration, m/s²", "jerk, m/s³"]):
        ax.plot(deg, c[key] * (1e3 if key == "lift_m" else 1.0))
        ax.set_ylabel(label)
    axes[-1].set_xlabel("crank angle, deg")
    out = sys.argv[1] if len(sys.argv) > 1 else "example1-svaj.png"
    fig.savefig(out, dpi=100)
    print(f"SVAJ plotted to {out}")
else:
    print("matplotlib is not installed: no plot (apt-get install python3-matplotlib)")

run = needle.simulate(case, series=True)
f = run["columns"]["contact_force_N"]
print(f"at {run['speed_rpm']:.0f} rpm ({run['method']}): lift-off {run['liftoff']}, "
      f"largest contact force {f.max():.1f} N over {len(f)} samples")

sweep = needle.overspeed(case)
n_dyn = sweep["liftoff_rpm_dynamic"]
print(f"n_qs {sweep['liftoff_rpm_quasi_static']:.1f} rpm, n_dyn "
      + (f"{n_dyn:.1f} rpm" if n_dyn is not None else "none in the range")
      + f" ({len(sweep['rows'])} speeds on {sweep['threads']} threads)")

case["needle"]["mass_kg"] *= 2  # a needle.Case reads and writes like a dict of its sections
heavy = needle.spring(case)
print(f"with twice the mass ({case['needle']['mass_kg']} kg): n_qs "
      f"{heavy['liftoff_rpm_quasi_static']:.1f} rpm")
