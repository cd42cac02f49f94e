#!/usr/bin/env python3
"""SciPy's solve_ivp against needle's `exact` on the same one-mass model (issue 53, item 4).

The bench's `soft` scene (cases/basu-cam4-light-spring.toml at 400 rpm, no play) written out
again in Python from docs/model.md §4: m y'' = F_c + F_s - (P0 + k y), compliant contacts
F = k g + c g' while g > 0 and F > 0 (c = 2 zeta sqrt(k m)), g_c = u - y, g_s = -y; the cam
input u is the case's own not-a-knot cubic through its table (SciPy's CubicSpline: the same
interpolant), 0 outside it. The contacts are gated inside the right-hand side (no events), as
a SciPy user would write them. Each of RK45, DOP853 and Radau runs at a ladder of tolerances;
its largest lift error on 2001 points of needle's window is taken against needle's `exact`
(itself within 5e-10 um of dopri5 at rtol 1e-12, BENCHMARKS.md). Times: the best of 3 runs
for SciPy, the median of 50 for needle (a bound needle.Scene, so no binding is counted).

Where a SciPy run stays less accurate than `exact`, the ratio at its most accurate run is a
lower bound of the ratio at equal lift error (more accuracy would take SciPy longer).

    PYTHONPATH=build/python /usr/bin/python3 bench/scipy_peer.py [--quick]

Writes bench/scipy-peer.md (BENCHMARKS.md takes it, scripts/bench.sh) and prints it.
"""
import argparse
import math
import os
import statistics
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp
from scipy.interpolate import CubicSpline

import needle

CASE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cases",
                    "basu-cam4-light-spring.toml")
RPM = 400.0


def Model(case):
    """The train's parameters, SI, read from the case as written (its keys are known)."""
    lift, spring, train = case["lift"], case["spring"], case["train"]
    if train.get("play_mm", 0) != 0:
        raise SystemExit("scipy_peer: the peer model has no play; the scene must have none")
    m = float(case["needle"]["mass_kg"])
    kc, ks = float(train["contact_stiffness_N_m"]), float(train["seat_stiffness_N_m"])
    return {
        "m": m,
        "P0": float(spring["preload_N"]),
        "k": float(spring["rate_N_mm"]) * 1e3,
        "kc": kc,
        "cc": 2.0 * float(train["contact_damping_ratio"]) * math.sqrt(kc * m),
        "ks": ks,
        "cs": 2.0 * float(train["seat_damping_ratio"]) * math.sqrt(ks * m),
        "spline": CubicSpline(np.radians(lift["crank_deg"]), np.array(lift["lift_mm"]) * 1e-3,
                              bc_type="not-a-knot"),
    }


def RightHandSide(model, theta_a, omega):
    s = model["spline"]
    ds = s.derivative()
    lo, hi = s.x[0], s.x[-1]
    m, P0, k = model["m"], model["P0"], model["k"]
    kc, cc, ks, cs = model["kc"], model["cc"], model["ks"], model["cs"]

    def f(t, x):
        y, v = x
        th = theta_a + omega * t
        if lo <= th <= hi:
            u, du = float(s(th)), omega * float(ds(th))
        else:
            u, du = 0.0, 0.0
        gc, gs = u - y, -y
        fc = kc * gc + cc * (du - v) if gc > 0.0 else 0.0
        fs = ks * gs - cs * v if gs > 0.0 else 0.0
        return [v, (max(fc, 0.0) + max(fs, 0.0) - (P0 + k * y)) / m]

    return f


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer tolerances")
    args = parser.parse_args()

    case = needle.load_case(CASE)
    model = Model(case.to_dict())
    scene = needle.Scene(CASE)
    first = scene.simulate(rpm=RPM, method="exact", dynamic=True)
    start, end = first["window_start_deg"], first["window_end_deg"]
    grid = list(np.linspace(start, end, 2001))
    truth = scene.simulate(rpm=RPM, method="exact", dynamic=True, grid_deg=grid)["grid"]
    grid_rad = np.radians(np.array(truth["crank_deg"]))
    truth_m = np.array(truth["lift_mm"]) * 1e-3

    times = []
    for _ in range(50):
        t0 = time.perf_counter()
        scene.simulate(rpm=RPM, method="exact", dynamic=True)
        times.append(time.perf_counter() - t0)
    exact_s = statistics.median(times)

    omega = RPM * 2.0 * math.pi / 60.0
    theta_a = math.radians(start)
    t_end = (math.radians(first["run_end_deg"]) - theta_a) / omega
    # The static start with both contacts pushing (the cam's base circle touches the seated
    # needle, play 0): k_c(0 − y) + k_s(−y) = P0 + k y.
    y0 = -model["P0"] / (model["kc"] + model["ks"] + model["k"])
    f = RightHandSide(model, theta_a, omega)
    t_grid = (grid_rad - theta_a) / omega

    ladder = [1e-3, 1e-5, 1e-7, 1e-9, 1e-11, 1e-13]
    if args.quick:
        ladder = [1e-4, 1e-8, 1e-12]
    rows = []
    for method in ("RK45", "DOP853", "Radau"):
        for rtol in ladder:
            if method == "Radau" and rtol < 1e-11:
                continue  # hours in pure Python at these tolerances
            best, sol = math.inf, None
            for _ in range(3):
                t0 = time.perf_counter()
                sol = solve_ivp(f, (0.0, t_end), [y0, 0.0], method=method, rtol=rtol,
                                atol=rtol * 1e-3, dense_output=True)
                best = min(best, time.perf_counter() - t0)
                if best > 20.0:
                    break
            if not sol.success:
                rows.append((method, rtol, best, math.nan, sol.nfev))
                continue
            error = float(np.max(np.abs(sol.sol(t_grid)[0] - truth_m)))
            rows.append((method, rtol, best, error, sol.nfev))
            print(f"{method} {rtol:g}: {best * 1e3:.1f} ms, {error * 1e6:.3g} um", file=sys.stderr)

    out = ["## SciPy's solve_ivp against `exact` (`bench/scipy_peer.py`)", "",
           f"The `soft` scene ({os.path.basename(CASE)}, {RPM:g} rpm) written again in Python "
           "(docs/model.md §4, the case's own not-a-knot cubic by SciPy's CubicSpline, contacts "
           "gated in the right-hand side); lift error on 2001 points of the window against "
           "`exact`; SciPy's best of 3 runs, needle's median of 50 calls of a bound "
           "`needle.Scene` (the Python call included).", "",
           "| SciPy method | rtol | ms | evaluations | lift error µm | time / exact's |",
           "|---|---|---|---|---|---|"]
    for method, rtol, s, error, nfev in rows:
        out.append(f"| {method} | {rtol:g} | {s * 1e3:.4g} | {nfev} | {error * 1e6:.3g} | "
                   f"{s / exact_s:.4g} |")
    best = {}
    for method, rtol, s, error, nfev in rows:
        if math.isfinite(error) and (method not in best or error < best[method][1]):
            best[method] = (s, error)
    out += ["", f"needle `exact`: {exact_s * 1e3:.3g} ms, its own lift error some 5e-10 µm "
            "(against dopri5 at rtol 1e-12, \"Method exact against dopri5\"). At each SciPy "
            "method's most accurate run, its time over exact's (where that run is still less "
            "accurate than exact, a lower bound of the ratio at equal error): " +
            ", ".join(f"{m} {v[0] / exact_s:.0f}× at {v[1] * 1e6:.2g} µm"
                      for m, v in best.items()) + "."]
    text = "\n".join(out) + "\n"
    with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "scipy-peer.md"), "w") as f:
        f.write(text)
    print(text, end="")


if __name__ == "__main__":
    main()
