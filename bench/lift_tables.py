#!/usr/bin/env python3
"""Lift tables as users export them: needle's differentiation against SciPy's peers.

    python3 bench/lift_tables.py [--quick] [--needle PATH] [--out DIR] [--jobs N] [--tables DIR]

Generates lift tables from closed-form cam laws (exact s, s', s''), writes each as a CSV the
way users export them (9 decimals, rounded to 1e-4 or 1e-3 mm, steps of 0.05-1 deg, with and
without base-circle padding, dense staircases of 5e4-1e6 rows, "measured" tables with
Gaussian noise), and for each table

  * runs `needle kinematics FILE.csv --rpm N --json` with no spline or noise settings and
    reads the largest and smallest acceleration (and their bands
    `max_acceleration_band_m_s2` / `min_acceleration_band_m_s2`, [lo, hi], when the binary
    gives them);
  * runs `needle spring CASE.toml --json` on a minimal case around the same CSV and reads the
    quasi-static lift-off speed n_qs (`liftoff_rpm_quasi_static`);
  * differentiates the same table with SciPy's `make_smoothing_spline` (GCV) and
    `savgol_filter` (deriv=2);

and compares all of them with the closed form. Writes DIR/lift-tables.csv (one row per table)
and DIR/lift-tables.md (the section `## Lift tables as users export them` of BENCHMARKS.md).
The tables themselves go to a temporary directory, removed at the end (`--tables DIR` keeps
them). Needs NumPy and SciPy >= 1.10 (Debian: python3-scipy); when the `python3` found first
lacks them (a pyenv shim, say), the script re-runs itself under Debian's /usr/bin/python3.
"""

import os
import re
import sys

from debian_python import reexec_or_exit

try:
    import numpy as np
    import scipy
    from scipy.interpolate import make_smoothing_spline
    from scipy.signal import savgol_filter
except ImportError:
    reexec_or_exit(__file__, "lift_tables.py: needs NumPy and SciPy >= 1.10 "
                   "(Debian: apt-get install python3-scipy)")

import argparse
import concurrent.futures
import csv
import json
import math
import multiprocessing
import shutil
import statistics
import subprocess
import tempfile
import time
from dataclasses import dataclass, field

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PEER_TIMEOUT_S = 60.0      # a peer that takes longer on one table is recorded as "> 60 s"
NEEDLE_TIMEOUT_S = 600.0   # one needle run
DENSE_ROWS = 20000         # tables at least this long are "dense": run alone, timed, peers in a child

# ---------------------------------------------------------------------------------------------
# Normalised motion laws f(x), x in [0, 1], f(0) = 0, f(1) = 1, with f' and f'' (d/dx).
# A rise of H over beta (rad) is s = H f(x), s' = H f'/beta, s'' = H f''/beta^2; a return is
# H (1 - f(x)). Sources: R. L. Norton, Cam Design and Manufacturing Handbook (2nd ed., 2009),
# ch. 3 ("double-dwell cam design"), and H. A. Rothbart (ed.), Cam Design Handbook (2004),
# ch. 2-3; the peak factors C_a = max f'' checked in self_test are Norton's (to his 3-4 digits).
# ---------------------------------------------------------------------------------------------


def shm(x):
    """Simple harmonic motion: f = (1 - cos pi x)/2. f'' jumps at both ends (C_a = pi^2/2)."""
    return (1 - np.cos(np.pi * x)) / 2, np.pi / 2 * np.sin(np.pi * x), np.pi ** 2 / 2 * np.cos(np.pi * x)


def cycloidal(x):
    """Cycloidal: f = x - sin(2 pi x)/(2 pi); f'' = 2 pi sin(2 pi x) (C_a = 2 pi)."""
    w = 2 * np.pi * x
    return x - np.sin(w) / (2 * np.pi), 1 - np.cos(w), 2 * np.pi * np.sin(w)


def poly345(x):
    """3-4-5 polynomial: f = 10x^3 - 15x^4 + 6x^5 (C_a = 5.7735)."""
    return (10 * x**3 - 15 * x**4 + 6 * x**5, 30 * x**2 - 60 * x**3 + 30 * x**4,
            60 * x - 180 * x**2 + 120 * x**3)


def poly4567(x):
    """4-5-6-7 polynomial: f = 35x^4 - 84x^5 + 70x^6 - 20x^7 (jerk zero at the ends; C_a = 7.5132
    at x = (5 - sqrt 5)/10, 7.51 in Norton's table)."""
    return (35 * x**4 - 84 * x**5 + 70 * x**6 - 20 * x**7,
            140 * x**3 - 420 * x**4 + 420 * x**5 - 140 * x**6,
            420 * x**2 - 1680 * x**3 + 2100 * x**4 - 840 * x**5)


def bspline_profile(t):
    """A cubic B-spline law (a CAD export's) on knots t (0 = t_0 < ... < t_m = 1, symmetric
    about 1/2): f'' piecewise linear between them, through the cycloidal's 2 pi sin(2 pi x) at
    each, so f''' jumps at every knot and f'' peaks at one (a V the readings' windows round off).
    f = sum c_k (x - t_k)+^3 / 6, scaled so that f(1) = 1 (symmetric knots: f'(1) = 0)."""
    t = np.asarray(t, dtype=float)
    slopes = 2 * np.pi * np.diff(np.sin(2 * np.pi * t)) / np.diff(t)
    c = np.diff(np.concatenate(([0.0], slopes)))

    def sums(xx):
        u = np.maximum(0.0, np.subtract.outer(np.asarray(xx, dtype=float), t[:-1]))
        return (u**3 / 6) @ c, (u**2 / 2) @ c, u @ c

    top = float(sums(np.array([1.0]))[0][0])

    def law(x):
        f, f1, f2 = sums(x)
        return f / top, f1 / top, f2 / top
    return law


cubic_bspline = bspline_profile(np.linspace(0.0, 1.0, 9))  # 9 equal knots, f'' peaks at x = 1/4


def _antisymmetric(half):
    """A law from its first half, f(x) = 1 - f(1 - x) beyond x = 1/2 (so f'' is odd about 1/2),
    scaled so that f(1/2) = 1/2; `half` is the unscaled law on [0, 1/2] with peak f'' = 1."""
    scale = 0.5 / float(half(np.array([0.5]))[0][0])

    def law(x):
        x = np.asarray(x, dtype=float)
        first = x <= 0.5
        f, f1, f2 = half(np.where(first, x, 1 - x))
        return (np.where(first, scale * f, 1 - scale * f), scale * f1,
                np.where(first, scale * f2, -scale * f2))
    return law


def _modified_sine_half(x):
    """Modified sine (Norton eq. 3.12; Rothbart): f'' = A sin(4 pi x) on [0, 1/8], then
    A cos(4 pi x/3 - pi/6) on [1/8, 7/8]; here its first half with A = 1, integrated in closed
    form (f' = (1 + 3 sin(4 pi x/3 - pi/6))/(4 pi) on the middle piece). Scaled, A = 5.5280."""
    k = 4 * np.pi
    f2a, f1a, fa = np.sin(k * x), (1 - np.cos(k * x)) / k, (x - np.sin(k * x) / k) / k
    p = k * x / 3 - np.pi / 6
    f_8 = (1 / 8 - 1 / k) / k                         # f(1/8) of the first piece
    f2b, f1b = np.cos(p), (1 + 3 * np.sin(p)) / k
    fb = f_8 + ((x - 1 / 8) - 9 / k * (np.cos(p) - 1)) / k
    first = x <= 1 / 8
    return np.where(first, fa, fb), np.where(first, f1a, f1b), np.where(first, f2a, f2b)


def _modified_trapezoid_half(x):
    """Modified trapezoid (Norton eq. 3.11; Rothbart): f'' = A sin(4 pi x) on [0, 1/8], A on
    [1/8, 3/8], A cos(4 pi (x - 3/8)) on [3/8, 5/8], ...; its first half with A = 1,
    integrated piece by piece. Scaled, A = 4.8881."""
    k = 4 * np.pi
    f2a, f1a, fa = np.sin(k * x), (1 - np.cos(k * x)) / k, (x - np.sin(k * x) / k) / k
    f_1, v_1 = (1 / 8 - 1 / k) / k, 1 / k               # f, f' at x = 1/8
    u = x - 1 / 8
    f2b, f1b, fb = np.ones_like(x), v_1 + u, f_1 + v_1 * u + u**2 / 2
    f_3, v_3 = f_1 + v_1 / 4 + 1 / 32, v_1 + 1 / 4      # f, f' at x = 3/8
    w = x - 3 / 8
    f2c, f1c = np.cos(k * w), v_3 + np.sin(k * w) / k
    fc = f_3 + v_3 * w + (1 - np.cos(k * w)) / k**2
    pieces = [x <= 1 / 8, (x > 1 / 8) & (x <= 3 / 8), x > 3 / 8]
    return (np.select(pieces, [fa, fb, fc]), np.select(pieces, [f1a, f1b, f1c]),
            np.select(pieces, [f2a, f2b, f2c]))


modified_sine = _antisymmetric(_modified_sine_half)
modified_trapezoid = _antisymmetric(_modified_trapezoid_half)

# ---------------------------------------------------------------------------------------------
# Laws in a table's own angle (crank or cam degrees), as pieces with exact s, s', s''.
# ---------------------------------------------------------------------------------------------


@dataclass
class Law:
    key: str                  # short name in the tables
    title: str                # what it is, for the Markdown
    angle: str                # "crank" or "cam": the CSV's header column, crank_deg or cam_deg
    pieces: list              # (from_deg, to_deg, fn); fn(theta_deg) -> (s mm, s' mm/rad, s'' mm/rad^2)
    rpm: float                # crank speed for --rpm and [engine] speed_rpm
    mass_kg: float            # the minimal case's [needle] and [spring]
    preload_N: float
    rate_N_mm: float
    rise_deg: float           # the rise's length (table degrees): Savitzky-Golay's window
    pad_deg: float = 10.0     # base-circle padding, table degrees, before and after
    truth: dict = field(default_factory=dict)

    @property
    def crank_per_deg(self):
        """Crank degrees per table degree: a four-stroke cam turns at half crank speed
        (docs/model.md §1), and needle reads a cam_deg table with --cycle four-stroke."""
        return 2.0 if self.angle == "cam" else 1.0

    @property
    def omega(self):
        """The table angle's rate, rad/s: the crank's, or the cam's at half of it."""
        return self.rpm * 2 * math.pi / 60 / self.crank_per_deg

    @property
    def open_deg(self):
        return self.pieces[0][0]

    @property
    def close_deg(self):
        return self.pieces[-1][1]

    def lift(self, theta):
        """s (mm) on any table angles; zero (the base circle) outside the open lift."""
        s = np.zeros_like(theta)
        for a, b, fn in self.pieces:
            m = (theta >= a) & (theta <= b)
            if m.any():
                s[m] = fn(theta[m])[0]
        return np.maximum(s, 0.0)   # the closed forms end at 0 to round-off; no "-0.000" rows


def rise_dwell_return(profile, lift_mm, start, rise, dwell, ret):
    """Pieces of a rise of lift_mm over `rise` deg from `start`, a dwell, and the same law's
    return over `ret` deg: s = H f(x) and s = H (1 - f(x)), derivatives by the chain rule."""
    def rise_fn(th):
        f, f1, f2 = profile((th - start) / rise)
        b = math.radians(rise)
        return lift_mm * f, lift_mm * f1 / b, lift_mm * f2 / b**2

    def dwell_fn(th):
        return np.full_like(th, lift_mm), np.zeros_like(th), np.zeros_like(th)

    back = start + rise + dwell

    def return_fn(th):
        f, f1, f2 = profile((th - back) / ret)
        b = math.radians(ret)
        return lift_mm * (1 - f), -lift_mm * f1 / b, -lift_mm * f2 / b**2

    pieces = [(start, start + rise, rise_fn)]
    if dwell > 0:
        pieces.append((start + rise, back, dwell_fn))
    pieces.append((back, back + ret, return_fn))
    return pieces


def circular_arc_cam(base_mm, lift_mm, nose_mm, half_deg):
    """A symmetric three-arc cam under a flat-faced translating follower (the classic "circular
    arc cam": base circle, flank arcs, nose arc; Rothbart, Cam Design Handbook, and Chen,
    Mechanics and Design of Cam Mechanisms). Closed form from the support function: a flat face
    normal to u(psi) = (cos psi, sin psi) touches the arc of centre c and radius rho at the
    distance c.u + rho, so the lift is s = c.u + rho - r_b, s' = c.u_perp, s'' = -c.u
    (psi the cam angle from the nose, rad). The nose's centre is at d = r_b + L - r_n on the
    axis; the flank's radius R_f is chosen so that the rise takes half_deg (flank internally
    tangent to the base circle and to the nose):
        R_f = (r_n^2 - r_b^2 - d^2 - 2 d r_b cos a) / (2 (r_n - r_b - d cos a)),  a = pi - half.
    s'' jumps at the four junctions: +(R_f - r_b) on the flank at the base circle, -d at the nose
    tip. Table angles: the nose at 0, the rise from -half_deg."""
    r_b, r_n = base_mm, nose_mm
    d = r_b + lift_mm - r_n
    alpha = math.pi - math.radians(half_deg)
    r_f = (r_n**2 - r_b**2 - d**2 - 2 * d * r_b * math.cos(alpha)) / (2 * (r_n - r_b - d * math.cos(alpha)))
    e = r_f - r_b                                            # |flank centre|
    c_f = (e * math.cos(alpha), e * math.sin(alpha))         # the rising flank's centre
    psi_t = math.degrees(math.atan2(-c_f[1], d - c_f[0]))    # flank-nose junction (negative)

    def flank(th):   # the rising flank; th in degrees from the nose
        p = np.radians(th) - alpha
        return e * (1 + np.cos(p)), -e * np.sin(p), -e * np.cos(p)

    def nose(th):
        p = np.radians(th)
        return d * np.cos(p) + r_n - r_b, -d * np.sin(p), -d * np.cos(p)

    def flank_back(th):  # mirror image: s(psi) = s(-psi), s' odd, s'' even
        s, s1, s2 = flank(-th)
        return s, -s1, s2

    pieces = [(-half_deg, psi_t, flank), (psi_t, -psi_t, nose), (-psi_t, half_deg, flank_back)]
    return pieces, r_f, psi_t


def make_laws():
    """The suite's laws. Needle laws: H = 3 mm in crank degrees, rise 24 deg, dwell 6, return 30
    (asymmetric, so the rise's deceleration and the return's are different), at 400 rpm, a 0.5 kg
    train on 600 N + 30 N/mm. Valve cams: cam degrees, a four-stroke cycle."""
    needle = dict(angle="crank", rpm=400.0, mass_kg=0.5, preload_N=600.0, rate_N_mm=30.0, rise_deg=24.0)
    laws = []
    for key, title, prof in [
        ("shm", "harmonic (SHM)", shm),
        ("cycloidal", "cycloidal", cycloidal),
        ("poly345", "3-4-5 polynomial", poly345),
        ("poly4567", "4-5-6-7 polynomial", poly4567),
        ("modsine", "modified sine", modified_sine),
        ("modtrap", "modified trapezoid", modified_trapezoid),
        ("bspline", "cubic B-spline (9 equal knots)", cubic_bspline),
    ]:
        laws.append(Law(key=key, title=f"{title}: 3 mm rise over 24 deg crank, dwell 6, return over 30",
                        pieces=rise_dwell_return(prof, 3.0, -12.0, 24.0, 6.0, 30.0), **needle))
    # The published SHM valve cam: rise 50 mm over 120 deg of cam, dwell 30, SHM return over 60,
    # cam at 100 rpm, peak accelerations 6.17 (rise) and 24.67 m/s^2 (return). A four-stroke
    # cam at 100 rpm is a crank at 200 rpm; the CSV says cam_deg and needle gets --cycle.
    laws.append(Law(key="shm-valve", angle="cam", rpm=200.0, mass_kg=0.5, preload_N=200.0, rate_N_mm=5.0,
                    title="published SHM valve cam: 50 mm over 120 deg cam, dwell 30, return over 60, 100 rpm cam",
                    pieces=rise_dwell_return(shm, 50.0, 0.0, 120.0, 30.0, 60.0), rise_deg=120.0))
    arc, r_f, psi_t = circular_arc_cam(20.0, 8.0, 4.0, 60.0)
    laws.append(Law(key="arc-cam", angle="cam", rpm=1500.0, mass_kg=0.3, preload_N=400.0, rate_N_mm=20.0,
                    title=(f"three-arc valve cam, flat-faced follower: base r 20 mm, lift 8, nose r 4, flank R "
                           f"{r_f:.1f} (rise 60 deg cam, flank-nose junction {60 + psi_t:.2f} deg into it), "
                           "750 rpm cam"), pieces=arc, rise_deg=60.0))
    for law in laws:
        law.truth = closed_form_truth(law)
    return laws


def closed_form_truth(law, n=200001):
    """a_max, a_min (m/s^2) over the open lift and n_qs (crank rpm), from the exact s''.
    Each piece is sampled on its closed interval with its own formula, so a jump of s'' at a
    junction counts with its one-sided limits; 2e5 points per piece put the peaks to ~1e-10.
    n_qs is needle's definition (docs/model.md §6, F_g = 0: the case gives no diameter):
        n_qs = (60/2 pi) sqrt( min over s'' < 0 of (P0 + k s) / (m |s''|) ),
    s'' with respect to crank angle in rad (a cam table's s'' / 4 in a four-stroke)."""
    a_max, a_min, g_min, per_piece = -math.inf, math.inf, math.inf, []
    for a, b, fn in law.pieces:
        th = np.linspace(a, b, n)
        s, _, s2 = fn(th)
        acc = law.omega**2 * s2 * 1e-3
        per_piece.append((float(acc.max()), float(acc.min())))
        a_max, a_min = max(a_max, float(acc.max())), min(a_min, float(acc.min()))
        s2c = s2 / law.crank_per_deg**2 * 1e-3                       # m per crank rad^2
        dec = s2c < 0
        if dec.any():
            g = (law.preload_N + law.rate_N_mm * 1e3 * s[dec] * 1e-3) / (law.mass_kg * -s2c[dec])
            g_min = min(g_min, float(g.min()))
    n_qs = 60 / (2 * math.pi) * math.sqrt(g_min) if math.isfinite(g_min) else math.inf
    return dict(a_max=a_max, a_min=a_min, n_qs=n_qs, per_piece=per_piece)


def self_test(laws):
    """Each profile ends where it should, its f' and f'' are the derivatives of its f, its
    peak factor is the handbook's; the SHM valve cam gives the published 6.17 and 24.67 m/s^2.
    Raises on a mismatch: a wrong closed form would make every row of the benchmark wrong."""
    x = np.linspace(0, 1, 200001)
    published = {shm: 4.9348, cycloidal: 6.2832, poly345: 5.7735, poly4567: 7.5132,
                 modified_sine: 5.5280, modified_trapezoid: 4.8881}
    for prof, c_a in published.items():
        f, f1, f2 = prof(x)
        assert abs(f[0]) < 1e-12 and abs(f[-1] - 1) < 1e-12 and abs(f1[0]) < 1e-9 and abs(f1[-1]) < 1e-9, prof
        inner = slice(1, -1)   # central differences; f'' may jump only at the piece ends of 1/8
        assert np.max(np.abs(np.gradient(f, x)[inner] - f1[inner])) < 1e-6, prof
        assert np.max(np.abs(np.gradient(f1, x)[inner] - f2[inner])) < 1e-3, prof
        assert abs(f2.max() - c_a) < 1e-4, (prof, f2.max(), c_a)
    for law in laws:
        for (a0, b0, fn0), (a1, _, fn1) in zip(law.pieces, law.pieces[1:]):   # s, s' continuous
            j0, j1 = fn0(np.array([b0])), fn1(np.array([a1]))
            assert abs(j0[0][0] - j1[0][0]) < 1e-9 and abs(j0[1][0] - j1[1][0]) < 1e-9, law.key
    valve = next(l for l in laws if l.key == "shm-valve")
    rise_peak, return_peak = valve.truth["per_piece"][0][0], -valve.truth["per_piece"][2][1]
    assert abs(rise_peak - 6.17) < 0.005 and abs(return_peak - 24.67) < 0.005, (rise_peak, return_peak)
    return rise_peak, return_peak

# ---------------------------------------------------------------------------------------------
# The suite: which tables, exported how.
# ---------------------------------------------------------------------------------------------

EXPORTS = {  # kind -> (label, decimals printed, target on a_max and a_min)
    "exact9": ("exact, printed to 9 decimals", 9, 0.01),
    "r1e-4": ("rounded to 1e-4 mm", 4, 0.02),
    "r1e-3": ("rounded to 1e-3 mm", 3, 0.05),
    "dense": ("dense, rounded to 1e-4 mm (a staircase)", 4, 0.02),
    # Measured tables: the brief names no target; docs/lift-data.md's for measured tables (6 %
    # on the extreme accelerations, 3 % on n_qs, i.e. half) is used. Printed to 1e-4 mm.
    "noise": ("measured (Gaussian noise), printed to 1e-4 mm", 4, 0.06),
}


@dataclass
class Table:
    law: str
    kind: str                 # a key of EXPORTS
    step: float = 0.0         # table degrees; 0 for a dense table given by rows
    rows: int = 0             # dense tables: the number of rows
    pad: bool = True
    noise_um: float = 0.0
    seed: int = 0
    nqs: bool = True          # run `needle spring` for n_qs
    to_seat: bool = False     # unpadded: go on to the first grid point on or past the lift's end

    @property
    def name(self):
        parts = [self.law, self.kind, f"{self.step:g}deg" if self.step else f"{self.rows}rows",
                 "pad" if self.pad else "nopad"]
        if self.noise_um:
            parts.append(f"{self.noise_um:g}um-seed{self.seed}")
        return "_".join(parts)

    @property
    def dense(self):
        return self.rows >= DENSE_ROWS


def full_suite():
    laws = ["shm", "cycloidal", "poly345", "poly4567", "modsine", "modtrap", "shm-valve", "arc-cam",
            "bspline"]
    tables = []
    for law in laws:                                   # 9 laws x 3 printings x 5 steps x 2 = 270
        for kind in ("exact9", "r1e-4", "r1e-3"):
            for step in (0.05, 0.1, 0.25, 0.5, 1.0):
                for pad in (False, True):
                    tables.append(Table(law, kind, step=step, pad=pad))
    for i, law in enumerate(laws):                     # measured: every law at 0.25 deg, 3 sigmas
        for j, sigma in enumerate((1.0, 2.0, 5.0)):
            tables.append(Table(law, "noise", step=0.25, noise_um=sigma, seed=1000 + 10 * i + j))
    for step in (0.1, 0.5, 1.0):                       # and the cycloidal law at other spacings
        for j, sigma in enumerate((1.0, 2.0, 5.0)):
            tables.append(Table("cycloidal", "noise", step=step, noise_um=sigma, seed=2000 + int(step * 10) + j))
    for law, rows in [("cycloidal", 50000), ("cycloidal", 200000), ("cycloidal", 1000000),
                      ("poly345", 50000), ("shm-valve", 200000), ("arc-cam", 1000000)]:
        tables.append(Table(law, "dense", rows=rows))
    return tables


def quick_suite():
    return [
        Table("cycloidal", "exact9", step=0.5),
        Table("cycloidal", "r1e-3", step=0.25, pad=False),
        Table("poly345", "r1e-4", step=0.1),
        Table("modtrap", "exact9", step=1.0, pad=False),
        Table("shm", "r1e-4", step=0.25),
        Table("shm-valve", "exact9", step=0.5),
        Table("arc-cam", "r1e-4", step=0.25),
        Table("modsine", "noise", step=0.25, noise_um=2.0, seed=7),
        Table("poly4567", "noise", step=0.5, noise_um=5.0, seed=8),
        Table("cycloidal", "dense", rows=50000),
    ]


def table_data(law, t):
    """The table's angles (table degrees) and the lift as printed (mm), and the CSV's text."""
    lo, hi = law.open_deg, law.close_deg
    if t.pad:
        lo, hi = lo - law.pad_deg, hi + law.pad_deg
    if t.rows:                                   # dense: rows evenly over the span
        theta = np.linspace(lo, hi, t.rows)
        angle_decimals = 9
    else:                                        # a user's grid from the first point: the last
        n = int(math.floor((hi - lo) / t.step + 1e-9))  # row is the last grid point <= the end
        if t.to_seat and lo + t.step * n < hi - 1e-9:   # or the first past it, on the seat
            n += 1
        theta = lo + t.step * np.arange(n + 1)
        angle_decimals = next(d for d in range(10) if abs(round(t.step, d) - t.step) < 1e-12)
    s = law.lift(theta)
    if t.noise_um:                               # measured: noise on every reading, seated too
        s = s + np.random.default_rng(t.seed).normal(0.0, t.noise_um * 1e-3, theta.size)
    decimals = EXPORTS[t.kind][1]
    printed = np.round(s, decimals)
    printed[printed == 0] = 0.0                  # no "-0.0000" rows
    text = f"{law.angle}_deg,lift_mm\n" + "\n".join(
        f"{a:.{angle_decimals}f},{v:.{decimals}f}" for a, v in zip(theta, printed)) + "\n"
    return theta, printed, text

# ---------------------------------------------------------------------------------------------
# needle and the peers.
# ---------------------------------------------------------------------------------------------


def run_needle(binary, args, timeout=NEEDLE_TIMEOUT_S, waits=3):
    """Runs `binary args`; returns (JSON or None, error text or None, wall time s). The binary
    may be rebuilt under the benchmark: while it is missing or busy, wait a minute and retry."""
    for attempt in range(waits + 1):
        try:
            t0 = time.perf_counter()
            p = subprocess.run([binary] + args, capture_output=True, text=True, timeout=timeout)
            wall = time.perf_counter() - t0
        except (FileNotFoundError, PermissionError, OSError) as e:   # missing, mid-link, ETXTBSY
            if attempt == waits:
                return None, f"failed: {binary}: {e}", math.nan
            time.sleep(60)
            continue
        except subprocess.TimeoutExpired:
            return None, f"failed: > {timeout:.0f} s", timeout
        if p.returncode in (0, 1):      # 1: a failing verdict (spring); the numbers are there
            try:
                return json.loads(p.stdout), None, wall
            except json.JSONDecodeError:
                return None, "failed: output is not JSON", wall
        line = (p.stderr.strip().splitlines() or [f"exit {p.returncode}"])[-1]
        return None, f"failed (exit {p.returncode}): {line}", wall
    return None, "failed", math.nan


def _number(j, key):
    v = j.get(key) if j else None
    return float(v) if isinstance(v, (int, float)) else None


def _band(j, key):
    v = j.get(key) if j else None
    if isinstance(v, (list, tuple)) and len(v) == 2 and all(isinstance(x, (int, float)) for x in v):
        return [float(v[0]), float(v[1])]
    return None


def peer_gcv(theta, lift, law):
    """SciPy's smoothing spline, lam=None (GCV), on the table as the user has it (angles in
    degrees); s'' scaled to rad and evaluated on a grid 4x finer than the table's inside the
    true open lift (the peers are told where the lift is open; needle finds it itself)."""
    spl = make_smoothing_spline(theta, lift)
    inside = (theta >= law.open_deg) & (theta <= law.close_deg)
    n = int(inside.sum())
    grid = np.linspace(law.open_deg, law.close_deg, 4 * n + 1 if n < 100000 else n)
    acc = law.omega**2 * spl.derivative(2)(grid) * (180 / math.pi) ** 2 * 1e-3
    return float(acc.max()), float(acc.min())


def savgol_window(law, step):
    """The window a reasonable user would pick: about 1/20 of the rise's points, odd, at least
    5 (order 3 needs more than 4 points)."""
    w = int(round(law.rise_deg / step / 20))
    w = max(w, 5)
    return w if w % 2 else w + 1


def peer_savgol(theta, lift, law):
    """SciPy's Savitzky-Golay filter, order 3, deriv=2, delta = the step (rad), default mode
    'interp'; a user gets s'' at the table's points, read inside the true open lift."""
    step = float(theta[1] - theta[0])
    d2 = savgol_filter(lift, savgol_window(law, step), 3, deriv=2, delta=math.radians(step))
    inside = (theta >= law.open_deg - 1e-9) & (theta <= law.close_deg + 1e-9)
    acc = law.omega**2 * d2[inside] * 1e-3
    return float(acc.max()), float(acc.min())


PEERS = {"gcv": peer_gcv, "savgol": peer_savgol}


def _peer_child(conn, peer, theta, lift, law):
    try:
        conn.send(("ok", PEERS[peer](theta, lift, law)))
    except Exception as e:   # noqa: BLE001 -- a peer's failure is a result, recorded as such
        conn.send(("failed", f"failed: {type(e).__name__}: {e}"[:200]))


def run_peer(peer, theta, lift, law, isolate):
    """(a_max, a_min) or an error text, and the wall time. Dense tables run the peer in a child
    process, ended after PEER_TIMEOUT_S."""
    t0 = time.perf_counter()
    if not isolate:
        try:
            return PEERS[peer](theta, lift, law), None, time.perf_counter() - t0
        except Exception as e:   # noqa: BLE001
            return None, f"failed: {type(e).__name__}: {e}"[:200], time.perf_counter() - t0
    ctx = multiprocessing.get_context("fork")
    parent, child = ctx.Pipe(duplex=False)
    proc = ctx.Process(target=_peer_child, args=(child, peer, theta, lift, law))
    proc.start()
    child.close()
    result = None
    if parent.poll(PEER_TIMEOUT_S):
        try:
            result = parent.recv()
        except EOFError:
            result = None
    wall = time.perf_counter() - t0
    if proc.is_alive():
        proc.terminate()
    proc.join()
    if result is None:
        if wall >= PEER_TIMEOUT_S:
            return None, f"> {PEER_TIMEOUT_S:.0f} s", wall
        return None, f"failed: the child ended (exit {proc.exitcode})", wall
    status, value = result
    return (value, None, wall) if status == "ok" else (None, value, wall)

# ---------------------------------------------------------------------------------------------
# One table, end to end.
# ---------------------------------------------------------------------------------------------


def rel(value, truth):
    return None if value is None else (value - truth) / abs(truth)


def judge(value, band, truth, tol):
    """Met when the value is within tol of the truth, or the truth lies inside the band and the
    band is no wider than 2 tol (relative to the truth)."""
    if value is not None and abs(value - truth) <= tol * abs(truth):
        return True
    return bool(band and band[0] <= truth <= band[1] and band[1] - band[0] <= 2 * tol * abs(truth))


def run_table(t, law, binary, workdir):
    theta, lift, text = table_data(law, t)
    csv_path = os.path.join(workdir, t.name + ".csv")
    with open(csv_path, "w") as f:
        f.write(text)
    tr = law.truth
    tol = EXPORTS[t.kind][2]
    r = dict(law=law.key, export=t.kind, step_deg=t.step if t.step else round(float(theta[1] - theta[0]), 9),
             angle=law.angle, rows=int(theta.size), padding="yes" if t.pad else "no", noise_um=t.noise_um,
             seed=t.seed if t.noise_um else "", target_pct=100 * tol,
             a_max_true=tr["a_max"], a_min_true=tr["a_min"], n_qs_true=tr["n_qs"])

    args = ["kinematics", csv_path, "--rpm", f"{law.rpm:g}", "--json"]
    if law.angle == "cam":
        args += ["--cycle", "four-stroke"]
    j, err, wall = run_needle(binary, args)
    r["needle_time_s"] = wall
    r["needle_error"] = (err or "").replace(workdir + os.sep, "")   # the table's name, not the temporary path
    r["spline"] = (j or {}).get("spline", "")
    r["a_max_needle"], r["a_min_needle"] = _number(j, "max_acceleration_m_s2"), _number(j, "min_acceleration_m_s2")
    r["a_max_band"], r["a_min_band"] = _band(j, "max_acceleration_band_m_s2"), _band(j, "min_acceleration_band_m_s2")
    r["a_max_err"], r["a_min_err"] = rel(r["a_max_needle"], tr["a_max"]), rel(r["a_min_needle"], tr["a_min"])

    r["n_qs_needle"], r["n_qs_band"], r["n_qs_err"] = None, None, None
    r["n_qs_error"] = "" if t.nqs else "not run"
    if t.nqs:
        case_path = os.path.join(workdir, t.name + ".toml")
        with open(case_path, "w") as f:
            f.write(f'title = "bench/lift_tables.py: {t.name}"\n'
                    f'[engine]\nspeed_rpm = {law.rpm:g}\ncycle = "four-stroke"\n'
                    f'[lift]\ncsv = "{t.name}.csv"\n'
                    f'[needle]\nmass_kg = {law.mass_kg:g}\n'
                    f'[spring]\npreload_N = {law.preload_N:g}\nrate_N_mm = {law.rate_N_mm:g}\n')
        js, errs, _ = run_needle(binary, ["spring", case_path, "--json"])
        r["n_qs_error"] = (errs or "").replace(workdir + os.sep, "")
        r["n_qs_needle"] = _number(js, "liftoff_rpm_quasi_static")
        r["n_qs_band"] = _band(js, "liftoff_rpm_quasi_static_band")
        r["n_qs_err"] = rel(r["n_qs_needle"], tr["n_qs"])

    for peer in PEERS:
        value, perr, pwall = run_peer(peer, theta, lift, law, isolate=t.dense)
        r[f"{peer}_time_s"] = pwall
        r[f"{peer}_error"] = perr or ""
        r[f"{peer}_a_max_err"] = rel(value[0], tr["a_max"]) if value else None
        r[f"{peer}_a_min_err"] = rel(value[1], tr["a_min"]) if value else None

    ok_max = judge(r["a_max_needle"], r["a_max_band"], tr["a_max"], tol)
    ok_min = judge(r["a_min_needle"], r["a_min_band"], tr["a_min"], tol)
    ok_nqs = judge(r["n_qs_needle"], r["n_qs_band"], tr["n_qs"], tol / 2) if t.nqs else True
    r["met"] = "met" if ok_max and ok_min and ok_nqs else "missed"
    mine = row_error(r, "")
    others = [row_error(r, p + "_") for p in PEERS]
    r["ahead"] = "yes" if mine is not None and all(o is None or mine < o for o in others) else "no"
    return r


def row_error(r, prefix):
    """A row's error for one differentiator: the larger |relative error| of a_max and a_min."""
    e = [r[f"{prefix}a_max_err"], r[f"{prefix}a_min_err"]]
    return None if any(x is None for x in e) else max(abs(x) for x in e)


def _work(t, binary, workdir):
    laws = {l.key: l for l in make_laws()}     # cheap; keeps the job self-contained
    return run_table(t, laws[t.law], binary, workdir)

# ---------------------------------------------------------------------------------------------
# Output.
# ---------------------------------------------------------------------------------------------


CSV_COLUMNS = ["law", "export", "step_deg", "angle", "rows", "padding", "noise_um", "seed",
               "a_max_true", "a_max_needle", "a_max_err", "a_max_band",
               "a_min_true", "a_min_needle", "a_min_err", "a_min_band",
               "n_qs_true", "n_qs_needle", "n_qs_err", "n_qs_band", "spline",
               "gcv_a_max_err", "gcv_a_min_err", "savgol_a_max_err", "savgol_a_min_err",
               "needle_time_s", "gcv_time_s", "savgol_time_s", "target_pct", "met", "ahead",
               "needle_error", "n_qs_error", "gcv_error", "savgol_error"]


def write_csv(rows, path):
    def cell(v):
        if v is None:
            return ""
        if isinstance(v, list):
            return f"[{v[0]:.6g}; {v[1]:.6g}]"
        if isinstance(v, float):
            return f"{v:.6g}"
        return v
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(CSV_COLUMNS)
        for r in rows:
            w.writerow([cell(r.get(c)) for c in CSV_COLUMNS])


def pct(e, signed=False):
    if e is None:
        return "–"
    return f"{100 * e:+.2f} %" if signed else f"{100 * e:.2f} %"


def group_of(r):
    if r["export"] == "noise":
        return f"measured, σ = {r['noise_um']:g} µm, printed to 1e-4 mm"
    return EXPORTS[r["export"]][0]


def stats(values, failures):
    """'worst / median' of |errors| in per cent, and how many runs gave no number (refused,
    failed or, for a peer, stopped after PEER_TIMEOUT_S: the full table says which)."""
    ok = [v for v in values if v is not None]
    text = f"{100 * max(ok):.2f} % / {100 * statistics.median(ok):.2f} %" if ok else "–"
    return text + (f" ({failures} gave none)" if failures else "")


def peer_cell(r, peer):
    if r[f"{peer}_error"]:
        return r[f"{peer}_error"].split(":")[0] if r[f"{peer}_error"].startswith("failed") else r[f"{peer}_error"]
    return f"{pct(r[peer + '_a_max_err'], True)}, {pct(r[peer + '_a_min_err'], True)}"


def band_text(b):
    return "–" if not b else f"[{b[0]:.5g}, {b[1]:.5g}]"


def write_markdown(rows, laws, path, quick, elapsed, binary, shm_check, binary_changed):
    groups = {}
    for r in sorted(rows, key=lambda r: (list(EXPORTS).index(r["export"]), r["noise_um"])):
        groups.setdefault(group_of(r), []).append(r)
    out = ["## Lift tables as users export them", ""]
    if quick:
        out += ["**Quick subset** (`--quick`): a few tables to try the script; the full suite is "
                "`python3 bench/lift_tables.py`.", ""]
    out += [
        f"How well needle differentiates a lift table as users export it, beside SciPy "
        f"{scipy.__version__}'s peers: {len(rows)} tables generated from closed-form laws (exact s, "
        "s′, s″), run through `needle kinematics FILE.csv --rpm N --json` (`--cycle four-stroke` for "
        "`cam_deg` tables) and `needle spring CASE.toml --json` with no spline or noise settings. "
        "Error: (computed − true)/|true| of the largest and smallest acceleration over the open lift; "
        "a row's error is the larger of the two. Regenerate with `python3 bench/lift_tables.py` "
        f"(this run: {elapsed / 60:.1f} min on {os.cpu_count()} cores; `--quick` for a small subset).",
        "",
        "- **Laws** (Norton, *Cam Design and Manufacturing Handbook*, ch. 3; Rothbart, *Cam Design "
        "Handbook*): " + "; ".join(f"`{l.key}`: {l.title}" for l in laws) + ".",
        f"- The published SHM valve cam reproduced by the closed form: rise {shm_check[0]:.3f} m/s², "
        f"return {shm_check[1]:.3f} m/s² (published 6.17 and 24.67); its table is in cam degrees, "
        "read by needle as a four-stroke cam (crank = 2 × cam, 200 rpm crank).",
        "- **Exports**: lift printed to 9 decimals, or rounded to 1e-4 or 1e-3 mm; steps 0.05–1° of the "
        "table's angle; starting at the rise's first point (no padding) or with 10° of base circle "
        "(zeros) before and after; dense tables of 5e4–1e6 rows rounded to 1e-4 mm (a staircase); "
        "measured tables with Gaussian noise of 1, 2 and 5 µm (fixed seeds, also on the seated "
        "readings), printed to 1e-4 mm.",
        "- **n_qs** (needle's definition, docs/model.md §6; no gas force): n_qs = (60/2π)·√(min over "
        "s″ < 0 of (P₀ + k·s)/(m·|s″|)), s″ in m per crank rad², from the closed form on 2e5 points per "
        "piece; needle's from a minimal case (`[lift] csv`, `[needle] mass_kg`, `[spring] preload_N`, "
        "`rate_N_mm`, `[engine] speed_rpm`, `cycle`).",
        "- **Peers**, on the same printed tables, told the true open lift (needle finds it itself): "
        "`make_smoothing_spline(deg, lift)` (lam=None: GCV), s″ on a grid 4× finer than the table's; "
        "`savgol_filter(lift, window, 3, deriv=2, delta=h)` with the window about 1/20 of the "
        "rise's points (odd, at least 5), s″ at the table's points. On dense tables each peer runs "
        f"in a child process stopped after {PEER_TIMEOUT_S:.0f} s.",
        "- **Targets** with no settings: a_max and a_min within 1 % (9 decimals), 2 % (1e-4 mm and the "
        "dense staircases), 5 % (1e-3 mm), 6 % (measured; docs/lift-data.md's target, the brief naming "
        "none), n_qs within half of that; or the truth inside needle's band "
        "(`max_acceleration_band_m_s2`, `min_acceleration_band_m_s2`, `liftoff_rpm_quasi_static_band`; "
        "read when the binary gives them) with the band no wider than "
        "twice the target. *Ahead*: needle's row error below both peers' (a failed peer counts as behind).",
        "",
        "| export | tables | needle worst / median | GCV spline worst / median | Savitzky–Golay worst / median "
        "| needle n_qs worst / median | targets met | needle ahead of both |",
        "|---|---|---|---|---|---|---|---|",
    ]
    groups_all = list(groups.items()) + [("**all**", rows)]
    for label, rs in groups_all:
        def col(prefix):
            return stats([row_error(r, prefix) for r in rs], sum(row_error(r, prefix) is None for r in rs))
        nq = [abs(r["n_qs_err"]) if r["n_qs_err"] is not None else None for r in rs if r["n_qs_error"] != "not run"]
        met = f"{sum(r['met'] == 'met' for r in rs)}/{len(rs)}"
        out.append(f"| {label} | {len(rs)} | {col('')} | {col('gcv_')} | {col('savgol_')} | "
                   f"{stats(nq, sum(v is None for v in nq)) if nq else 'not run'} | "
                   f"{'**' + met + '**' if rs is rows else met} | {sum(r['ahead'] == 'yes' for r in rs)}/{len(rs)} |")
    dense = [r for r in rows if r["rows"] >= DENSE_ROWS]
    out += ["", "needle's run time (`kinematics`, wall, one process alone) on the dense tables: " +
            (", ".join(f"{r['law']} {r['rows']:,} rows {r['needle_time_s']:.2f} s" for r in dense) or "none run") +
            ". Other tables ran two at a time (`--jobs`); their times are in the CSV."]
    reasons = {}   # needle's refusals and failures, numbers blanked so that alike ones group
    for r in rows:
        for e in (r["needle_error"], r["n_qs_error"] if r["n_qs_error"] != "not run" else ""):
            if e:
                e = re.sub(r"^.*\.(csv|toml)(:\d+)*:\s*", "", e)   # the file and line: past the last
                key = re.sub(r"-?\d+(\.\d+)?(e[-+]?\d+)?", "#", e).split(": ")[0][:90]
                reasons.setdefault(key, set()).add((r["law"], r["export"], r["step_deg"], r["padding"]))
    if reasons:
        out += ["", "needle gave no number (kinematics or spring) on: " + "; ".join(
            f"{len(tables)} table(s), `{key}`" for key, tables in sorted(reasons.items(), key=lambda kv: -len(kv[1])))
            + "."]
    if binary_changed:
        out += ["", f"**Note**: `{binary}` changed during the run (rebuilt): rows may mix two builds."]
    out += ["", f"<details><summary>All {len(rows)} tables (bench/lift-tables.csv holds every number)</summary>", "",
            "| law | export | step ° | rows | pad | σ µm | a_max true | needle | err | band | a_min true | needle "
            "| err | band | n_qs true | needle | err | spline | GCV err (max, min) | S–G err (max, min) | needle s "
            "| met | ahead |",
            "|" + "---|" * 23]
    for r in rows:
        def num(v, f="{:.5g}"):
            return "–" if v is None else f.format(v)
        out.append(
            f"| {r['law']} | {r['export']} | {r['step_deg']:g} | {r['rows']} | {r['padding']} | {r['noise_um']:g} | "
            f"{num(r['a_max_true'])} | {num(r['a_max_needle']) if not r['needle_error'] else 'failed'} | "
            f"{pct(r['a_max_err'], True)} | {band_text(r['a_max_band'])} | {num(r['a_min_true'])} | "
            f"{num(r['a_min_needle']) if not r['needle_error'] else 'failed'} | {pct(r['a_min_err'], True)} | "
            f"{band_text(r['a_min_band'])} | {num(r['n_qs_true'], '{:.1f}')} | "
            f"{num(r['n_qs_needle'], '{:.1f}') if r['n_qs_error'] in ('', None) else r['n_qs_error'].split(':')[0]} | "
            f"{pct(r['n_qs_err'], True)} | {r['spline'] or '–'} | {peer_cell(r, 'gcv')} | {peer_cell(r, 'savgol')} | "
            f"{num(r['needle_time_s'], '{:.3f}')} | {r['met']} | {r['ahead']} |")
    out += ["", "</details>", ""]
    with open(path, "w") as f:
        f.write("\n".join(out))
    return out

# ---------------------------------------------------------------------------------------------


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="a small subset of the tables, for trying")
    ap.add_argument("--needle", default=os.path.join(ROOT, "build", "needle"), help="the needle binary")
    ap.add_argument("--out", default=os.path.join(ROOT, "bench"), help="where lift-tables.csv/.md go")
    ap.add_argument("--jobs", type=int, default=2, help="tables run at once (dense tables run alone)")
    ap.add_argument("--tables", help="keep the generated CSV tables and cases in this directory")
    a = ap.parse_args()

    laws = make_laws()
    shm_check = self_test(laws)
    suite = quick_suite() if a.quick else full_suite()
    binary = os.path.abspath(a.needle)
    for _ in range(10):      # the binary may be mid-build (another engineer's): wait for it
        if os.access(binary, os.X_OK):
            break
        print(f"lift_tables: {binary} is missing; waiting a minute for a build", file=sys.stderr)
        time.sleep(60)
    else:
        sys.exit(f"lift_tables: no needle binary at {binary} (build it, or give --needle PATH)")
    os.makedirs(a.out, exist_ok=True)
    workdir = os.path.abspath(a.tables) if a.tables else tempfile.mkdtemp(prefix="lift-tables-")
    os.makedirs(workdir, exist_ok=True)
    stamp = lambda: os.stat(binary).st_mtime if os.path.exists(binary) else None  # noqa: E731
    first_stamp = stamp()
    print(f"lift_tables: {len(suite)} tables, needle {binary}, tables in {workdir}", file=sys.stderr)
    t0 = time.perf_counter()
    rows = []
    try:
        small = [t for t in suite if not t.dense]
        with concurrent.futures.ProcessPoolExecutor(max_workers=max(1, a.jobs)) as pool:
            futures = [pool.submit(_work, t, binary, workdir) for t in small]
            for i, fut in enumerate(futures):
                rows.append(fut.result())
                if (i + 1) % 20 == 0 or i + 1 == len(futures):
                    print(f"lift_tables: {i + 1}/{len(suite)} tables", file=sys.stderr)
        for t in (t for t in suite if t.dense):          # alone, so that their times mean something
            rows.append(_work(t, binary, workdir))
            print(f"lift_tables: {t.name}: needle {rows[-1]['needle_time_s']:.2f} s", file=sys.stderr)
    finally:
        if not a.tables:
            shutil.rmtree(workdir, ignore_errors=True)
    elapsed = time.perf_counter() - t0
    write_csv(rows, os.path.join(a.out, "lift-tables.csv"))
    md = write_markdown(rows, laws, os.path.join(a.out, "lift-tables.md"), a.quick, elapsed, a.needle,
                        shm_check, stamp() != first_stamp)
    # The summary table on stdout.
    start = next(i for i, line in enumerate(md) if line.startswith("| export |"))
    end = next(i for i in range(start, len(md)) if not md[i].startswith("|"))
    print("\n".join(md[start:end]))
    print(f"lift_tables: wrote {a.out}/lift-tables.csv and lift-tables.md in {elapsed:.0f} s", file=sys.stderr)


if __name__ == "__main__":
    main()
