#!/usr/bin/env python3
"""docs/fit.md's worked example, regenerated from the program.

    python3 scripts/fit_example.py --write [--needle build/needle]   # traces, figure and block
    python3 scripts/fit_example.py --check [--needle build/needle]   # the block against the program

--write makes the example's bench traces (docs/fit/trace-400rpm.csv, trace-700rpm.csv) with the
Python module: Basu's Example 1 as built (a spring relaxed to 711 kgf, a 13 kg needle, a roller
contact of 3e8 N/m), its needle lift at 0.05° steps read by needle.simulate(grid_deg=…), plus
Gaussian noise of 5 µm (numpy, seed 477), written as a sensor's CSV; then runs the three fits of
the document on them and writes the block between the markers and the figure
docs/fit/fit-example.png (gnuplot). --check runs the same fits on the committed traces and fails
when the block differs: a documented number that no longer matches the program fails the test
`documented_fit`. Nothing in the block is typed by hand; run times are left out of it.
"""
import json
import pathlib
import subprocess
import sys
import tempfile

from doc_block import Block, WriteOrCheck

ROOT = pathlib.Path(__file__).resolve().parent.parent
DOC = ROOT / "docs" / "fit.md"
DATA = ROOT / "docs" / "fit"
CASE = ROOT / "cases" / "basu-example1.toml"
BEGIN = "<!-- fit-example: begin (scripts/fit_example.py) -->"
END = "<!-- fit-example: end -->"
TRUTH = {"spring.preload_kgf": 711.0, "needle.mass_kg": 13.0,
         "train.contact_stiffness_N_m": 3e8}
SPEEDS = (400, 700)
NOISE_MM = 0.005


def Trace(rpm):
    return DATA / ("trace-%drpm.csv" % rpm)


def MakeTraces():
    sys.path.insert(0, str(ROOT / "build" / "python"))
    import numpy as np
    import needle
    case = needle.load_case(str(CASE)).to_dict()
    case["spring"]["preload_kgf"] = TRUTH["spring.preload_kgf"]
    case["needle"]["mass_kg"] = TRUTH["needle.mass_kg"]
    case["train"]["contact_stiffness_N_m"] = TRUTH["train.contact_stiffness_N_m"]
    case = needle.load_case(case, name=str(CASE))
    rng = np.random.default_rng(477)
    grid = np.round(np.arange(-30.0, 70.0 + 1e-9, 0.05), 2)
    DATA.mkdir(exist_ok=True)
    for rpm in SPEEDS:
        run = needle.simulate(case, rpm=rpm, grid_deg=grid, dynamic=True)
        lift = np.array(run["grid"]["lift_mm"]) + rng.normal(0.0, NOISE_MM, grid.size)
        with open(Trace(rpm), "w") as f:
            f.write("# needle fit's worked example (docs/fit.md, scripts/fit_example.py): Basu's "
                    "Example 1 as built, at %d rpm, 5 um noise\ncrank_deg,lift_mm\n" % rpm)
            for d, y in zip(grid, lift):
                f.write("%.2f,%.5f\n" % (d, y))


def Fit(needle, traces, free, extra=()):
    # Run from the top of the tree with relative paths: the messages name the files as the
    # document shows them, wherever the tree is.
    cmd = [needle, "fit", str(CASE.relative_to(ROOT)), "--free", ",".join(free), "--json"]
    cmd += list(extra)
    for rpm in traces:
        cmd += ["--trace", str(Trace(rpm).relative_to(ROOT)), "--rpm", str(rpm)]
    run = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
    if run.returncode != 0:
        sys.exit("fit_example: %s: exit %d: %s" % (" ".join(cmd), run.returncode, run.stderr))
    return cmd, json.loads(run.stdout)


def G(v, digits=4):
    return "%.*g" % (digits, v)


def Shown(cmd):
    words = ["needle" if w.endswith("/needle") else w for w in cmd if w != "--json"]
    return " ".join(words)


def Table(d):
    rows = ["| key | case | fitted | 95 % interval | true |", "|---|---|---|---|---|"]
    for key, p in d["parameters"].items():
        note = "" if p["identified"] else " (not identified)"
        rows.append("| `%s` | %s | %s | %s to %s%s | %s |" % (
            key, G(p["start"]), G(p["value"], 5), G(p["low"], 5), G(p["high"], 5), note,
            G(TRUTH[key]) if key in TRUTH else "—"))
    return rows


def Block3(needle):
    out = []
    cmd, both = Fit(needle, SPEEDS, list(TRUTH))
    out += ["**1. Both traces, three unknowns.**", "", "```", Shown(cmd), "```", ""] + Table(both)
    traces = "; ".join("%s at %d rpm: residual RMS %s mm against its noise %s mm" % (
        pathlib.Path(t["path"]).name, t["speed_rpm"], G(t["residual_rms_mm"], 3),
        G(t["noise_mm"], 3)) for t in both["traces"])
    l = both["liftoff_rpm_dynamic"]
    run = subprocess.run([needle, "overspeed", str(CASE), "--json"], capture_output=True,
                         text=True)
    as_written = json.loads(run.stdout)["liftoff_rpm_dynamic"]
    out += ["", "Reduced χ² %s; %s. n_dyn of the calibrated case: **%s rpm** (95 %% range %s to %s "
            "rpm over %d draws of the parameters); the case as written says %s rpm." % (
                G(both["model"]["chi2_reduced"], 3), traces, G(l["value"], 4), G(l["low"], 4),
                G(l["high"], 4), l["draws"], G(as_written, 4))]
    for u in both["unseparated"]:
        out += ["", "The fit's own warning: *%s*." % u["advice"]]
    cmd, miss = Fit(needle, SPEEDS, ["spring.preload_kgf", "needle.mass_kg"], ["--no-liftoff"])
    out += ["", "**2. The contact stiffness left at the case's 1e9 N/m.**", "", "```", Shown(cmd),
            "```", ""] + Table(miss) + ["", "The fit says: *%s*." % miss["model"]["note"]]
    cmd, one = Fit(needle, (400,), list(TRUTH), ["--no-liftoff"])
    out += ["", "**3. The 400 rpm trace alone.**", "", "```", Shown(cmd), "```", ""] + Table(one)
    for u in one["unseparated"]:
        out += ["", "The fit says: *%s*." % u["advice"]]
    return "\n".join(out), both


def Figure(needle_bin, both):
    sys.path.insert(0, str(ROOT / "build" / "python"))
    import numpy as np
    import needle
    case = needle.load_case(str(CASE)).to_dict()
    for key, p in both["parameters"].items():
        section, name = key.split(".")
        case[section][name] = p["value"]
    case = needle.load_case(case, name=str(CASE))
    with tempfile.TemporaryDirectory() as tmp:
        plots = []
        for k, rpm in enumerate(SPEEDS):
            data = np.loadtxt(Trace(rpm), delimiter=",", comments="#", skiprows=2)
            run = needle.simulate(case, rpm=rpm, grid_deg=data[:, 0], dynamic=True)
            fitted = np.array(run["grid"]["lift_mm"])
            path = pathlib.Path(tmp) / ("%d.dat" % rpm)
            np.savetxt(path, np.column_stack([data, fitted, data[:, 1] - fitted]))
            plots.append((rpm, path))
        script = ["set terminal pngcairo size 900,620 font ',10'",
                  "set output '%s'" % (DATA / "fit-example.png"),
                  "set multiplot layout 2,1", "set grid", "set key top right",
                  "set ylabel 'lift (mm)'"]
        script.append("plot " + ", ".join(
            "'%s' using 1:2 with points pt 7 ps 0.2 lc %d title 'measured, %d rpm', "
            "'%s' using 1:3 with lines lw 2 lc %d title 'fitted, %d rpm'" % (p, k + 1, rpm, p, k + 1,
                                                                          rpm)
            for k, (rpm, p) in enumerate(plots)))
        script += ["set xlabel 'crank angle (deg)'", "set ylabel 'measured − fitted (mm)'"]
        script.append("plot " + ", ".join(
            "'%s' using 1:4 with points pt 7 ps 0.2 lc %d title '%d rpm'" % (p, k + 1, rpm)
            for k, (rpm, p) in enumerate(plots)))
        subprocess.run(["gnuplot"], input="\n".join(script) + "\n", text=True, check=True)


def main():
    a = WriteOrCheck(__doc__.splitlines()[0], lambda p: p.add_argument(
        "--needle", default=str(ROOT / "build" / "needle")))
    a.needle = str(pathlib.Path(a.needle).resolve())
    if a.write:
        MakeTraces()
    text, both = Block3(a.needle)
    block = Block(DOC, BEGIN, END, "fit_example")
    if a.write:
        block.Write(text)
        Figure(a.needle, both)
        print("wrote docs/fit/ traces, figure and docs/fit.md's example")
    elif block.old.strip("\n") != text:
        sys.exit("fit_example: docs/fit.md's worked example differs from the program; run "
                 "python3 scripts/fit_example.py --write")
    else:
        print("fit_example: docs/fit.md's worked example as documented")


if __name__ == "__main__":
    main()
