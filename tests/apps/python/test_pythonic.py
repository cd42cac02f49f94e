"""The module speaks Python (issue 38): keyword errors name the keyword and print its value as
Python does; every function takes a path, an os.PathLike, a needle.Case or a dict; a
needle.Case reads and writes like a dict of its sections and is validated as its file would be;
cycle= is checked; a huge integer names its key; no NumPy, no import. Run by ctest with
PYTHONPATH=build/python and NEEDLE_BINARY=build/needle."""
import json
import os
import pathlib
import subprocess
import sys
import tomllib

import numpy as np
import pytest

import needle

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
BINARY = os.environ.get("NEEDLE_BINARY", os.path.join(ROOT, "build", "needle"))
EXAMPLE1 = os.path.join(ROOT, "cases", "basu-example1.toml")
CSV = os.path.join(ROOT, "cases", "measured-cycloidal.csv")


def cli_error(*args):
    p = subprocess.run([BINARY, *args, "--json"], capture_output=True, text=True)
    assert p.returncode == 2, p.stdout
    return p.stderr.strip()


def message(call):
    with pytest.raises(needle.CaseError) as e:
        call()
    return str(e.value)


def data_of(path):
    with open(path, "rb") as f:
        return tomllib.load(f)


def same(a, b):
    a, b = dict(a), dict(b)
    a.pop("columns"), b.pop("columns")
    return a == b


# Keywords: named as written, values as Python prints them.

def test_keyword_errors_name_the_keyword_and_print_pythons_number():
    case = needle.load_case(EXAMPLE1)
    assert message(lambda: needle.simulate(case, rtol=0.0)) == \
        "rtol=0.0: expected a relative tolerance in [1e-14, 1e-2]"
    assert message(lambda: needle.simulate(case, rtol=1e-20)) == \
        "rtol=1e-20: expected a relative tolerance in [1e-14, 1e-2]"
    assert message(lambda: needle.kinematics(case, rpm=1e-20)) == \
        "rpm=1e-20: expected a speed in rpm in [1, 50000]"
    assert message(lambda: needle.kinematics(case, step_deg=0.0)) == \
        "step_deg=0.0: expected a spacing in crank degrees in [0.001, 90]"
    assert message(lambda: needle.overspeed(case, from_rpm=0)) == \
        "from_rpm=0: expected a speed in rpm in [1, 50000]"
    assert message(lambda: needle.overspeed(case, step_rpm=-1.5)) == \
        "step_rpm=-1.5: expected a speed step in rpm in [0.001, 1000000]"
    assert message(lambda: needle.overspeed(case, threads=-1)) == \
        "threads=-1: expected a number of threads in [0, 4096]"
    assert message(lambda: needle.tolerance(case, samples=0)) == \
        "samples=0: expected a number of samples in [1, 1000000]"
    assert message(lambda: needle.tolerance(case, seed=2**64)) == \
        "seed=18446744073709551616: expected a whole number in [0, 18446744073709551615]"
    assert message(lambda: needle.kinematics(case, spline="cubic")) == (
        "spline='cubic': unknown kind; expected one of natural, not-a-knot, clamped, quintic, "
        "pchip, makima, smoothing, local")


def test_a_call_pybind11_cannot_match_is_one_line_naming_the_argument():
    # Issue 51: pybind11's own TypeError lists every signature over several lines.
    def type_error(call):
        with pytest.raises(TypeError) as e:
            call()
        assert "\n" not in str(e.value)
        return str(e.value)
    assert type_error(lambda: needle.kinematics(EXAMPLE1, rmp=400)) == (
        "kinematics() got an unexpected keyword argument 'rmp'; expected one of case, rpm, "
        "step_deg, spline")
    assert type_error(lambda: needle.tolerance_reduce(EXAMPLE1, [], sed=1)) == (
        "tolerance_reduce() got an unexpected keyword argument 'sed'; expected one of case, "
        "shards, seed, first_sample, threads, seconds")
    assert type_error(lambda: needle.spring(EXAMPLE1, 400)) == (
        "spring() takes 1 positional argument(s) (case), got 2; give rpm by keyword")
    assert type_error(lambda: needle.size(EXAMPLE1, 400)) == (
        "size() takes 1 positional argument(s) (case), got 2")
    assert type_error(lambda: needle.tolerance_reduce(EXAMPLE1, [])) == (
        "tolerance_reduce() missing the argument 'seed'; it takes case, shards, seed, "
        "first_sample, threads, seconds")
    assert type_error(lambda: needle.spring(EXAMPLE1, case=EXAMPLE1)) == (
        "spring() got argument 'case' by position and by keyword; it takes case, rpm")
    # The functions keep their signature and their doc.
    assert needle.spring.__doc__.startswith("spring(case: object, *, rpm: object = None) -> dict")
    assert needle.spring(case=EXAMPLE1, rpm=125)["exit_status"] == 0


def test_a_commands_own_message_names_the_keyword():
    # The command's check after the case is read ("--spline: …" on the command line).
    small = {"engine": {"speed_rpm": 1000},
             "lift": {"crank_deg": [0, 10, 20, 30, 40], "lift_mm": [0, 1, 2, 1, 0]}}
    assert message(lambda: needle.kinematics(small, spline="quintic")) == \
        "<dict>: spline='quintic': \"quintic\" needs at least 6 points, the lift table has 5"


def test_a_bool_or_a_string_is_not_a_number():
    case = needle.load_case(EXAMPLE1)
    assert message(lambda: needle.kinematics(case, rpm=True)) == \
        "rpm=True: expected a speed in rpm in [1, 50000], not a bool"
    assert message(lambda: needle.spring(case, rpm="3000")) == \
        "rpm='3000': expected a speed in rpm in [1, 50000], not a str"
    assert message(lambda: needle.tolerance(case, samples=10.0)) == \
        "samples=10.0: expected a number of samples in [1, 1000000], not a float"
    assert message(lambda: needle.overspeed(case, threads=False)) == \
        "threads=False: expected a number of threads in [0, 4096], not a bool"
    assert message(lambda: needle.simulate(case, series=1)) == \
        "series=1: expected True or False, not an int"


def test_an_integer_too_large_names_its_key(tmp_path):
    case = needle.load_case(EXAMPLE1)
    assert message(lambda: needle.kinematics(case, rpm=10**400)) == \
        "rpm=" + "1" + "0" * 29 + "…(401 characters): expected a speed in rpm in [1, 50000]"
    # In a case: beyond 64 bits, the number it is, judged as the file judges it.
    bad = tmp_path / "fast.toml"
    bad.write_text("[engine]\nspeed_rpm = 1e30\n")
    assert "needle: " + message(lambda: needle.load_case(
        {"engine": {"speed_rpm": 10**30}}, name=str(bad))) == cli_error("spring", str(bad))
    assert message(lambda: needle.load_case({"engine": {"speed_rpm": 10**400}})) == \
        "<dict>: [engine] speed_rpm: " + "1" + "0" * 29 + \
        "…(401 characters) is too large for a number (a double)"



def test_numpy_numbers_are_numbers_and_numpy_bools_are_not():
    case = needle.load_case(EXAMPLE1)
    assert needle.kinematics(case, rpm=np.float32(300))["speed_rpm"] == 300.0
    assert needle.overspeed(case, threads=np.int64(1))["threads"] == 1
    assert message(lambda: needle.kinematics(case, rpm=np.True_)) == \
        f"rpm={np.True_!r}: expected a speed in rpm in [1, 50000], not a {type(np.True_).__name__}"
    assert message(lambda: needle.overspeed(case, threads=np.int64(-1))) == \
        f"threads={np.int64(-1)!r}: expected a number of threads in [0, 4096]"


# Sources: a path, an os.PathLike, a needle.Case or a dict, for every function.

def test_every_function_takes_a_path_a_pathlike_a_case_or_a_dict():
    case = needle.load_case(EXAMPLE1)
    for command in ("kinematics", "spring", "simulate", "profile"):
        f = getattr(needle, command)
        expected = f(case)
        assert same(f(EXAMPLE1), expected), command
        assert same(f(pathlib.Path(EXAMPLE1)), expected), command
        assert f(data_of(EXAMPLE1))["exit_status"] == expected["exit_status"], command
    spec = os.path.join(ROOT, "cases", "matec-2018-synth.toml")
    assert same(needle.synth(pathlib.Path(spec)), needle.synth(spec))
    assert same(needle.spring(needle.Case(pathlib.Path(EXAMPLE1))), needle.spring(case))
    with pytest.raises(TypeError) as e:
        needle.spring(42)
    assert str(e.value) == \
        "spring: expected a path (str or os.PathLike), a needle.Case or a dict, got an int"
    with pytest.raises(TypeError) as e:
        needle.load_case(None)
    assert str(e.value) == \
        "load_case: expected a path (str or os.PathLike), a needle.Case or a dict, got a NoneType"


# needle.Case: a dict of its sections.

def test_a_case_reads_like_a_dict_of_its_sections():
    case = needle.load_case(pathlib.Path(EXAMPLE1))
    data = data_of(EXAMPLE1)
    assert case.path == EXAMPLE1
    assert dict(case) == data and case.to_dict() == data
    # In the TOML reader's order (by name), not the file's.
    assert list(case.keys()) == sorted(data.keys()) and len(case) == len(data)
    assert "train" in case and "tolerance" not in case
    assert case["needle"]["mass_kg"] == data["needle"]["mass_kg"]
    assert case.get("tolerance") is None
    with pytest.raises(KeyError) as e:
        case["tolerance"]
    assert e.value.args == ("tolerance",)
    copy = case.to_dict()
    copy["needle"]["mass_kg"] = 99.0
    assert case["needle"]["mass_kg"] == data["needle"]["mass_kg"], "to_dict is a copy"


def test_a_changed_case_runs_as_the_changed_file(tmp_path):
    case = needle.load_case(EXAMPLE1)
    before = needle.spring(case)
    case["needle"]["mass_kg"] = 1.6
    data = data_of(EXAMPLE1)
    data["needle"]["mass_kg"] = 1.6
    after = needle.spring(case)
    assert same(after, needle.spring(needle.load_case(data, name=EXAMPLE1)))
    assert not same(after, before)
    # A bad change: the file's message, when run.
    case["needle"]["mass_kg"] = -1.0
    bad = tmp_path / "bad.toml"
    bad.write_text(open(EXAMPLE1).read().replace("mass_kg = ", "mass_kg = -1.0 #", 1))
    msg = message(lambda: needle.spring(case))
    assert msg == EXAMPLE1 + ": [needle] mass_kg: must be positive, got -1 kg"
    assert "needle: " + msg.replace(EXAMPLE1, str(bad)) == cli_error("spring", str(bad))
    case["needle"]["mass_kg"] = 1.6
    assert same(needle.spring(case), after)


def test_assigning_or_deleting_a_section_validates():
    case = needle.load_case(EXAMPLE1)
    engine = dict(case["engine"])
    with pytest.raises(needle.CaseError) as e:
        case["engine"] = {"speed_rpm": 0}
    assert str(e.value) == EXAMPLE1 + ": [engine] speed_rpm: must be positive, got 0"
    assert case["engine"] == engine, "a refused assignment changes nothing"
    with pytest.raises(needle.CaseError) as e:
        del case["engine"]
    assert str(e.value) == \
        EXAMPLE1 + ": [engine] speed_rpm: section [engine] is missing; it needs speed_rpm"
    assert "engine" in case
    case["engine"] = {"speed_rpm": 200, "cycle": "four-stroke"}
    assert case.speed_rpm == 200.0
    del case["paper"]
    assert "paper" not in case


# cycle= and bare CSV tables.

def test_a_cycle_typo_is_refused_as_the_command_line_does():
    assert message(lambda: needle.load_case(CSV, cycle="two-strok")) == \
        "cycle='two-strok': expected 'four-stroke' or 'two-stroke'"
    assert cli_error("kinematics", CSV, "--rpm", "1000", "--cycle", "two-strok").startswith(
        "needle: --cycle: two-strok not in")
    assert message(lambda: needle.load_case(EXAMPLE1, cycle="two-stroke")) == \
        "cycle='two-stroke': only for a bare CSV lift table; a case states [engine] cycle"
    two = needle.load_case(CSV, cycle="two-stroke")
    assert two["engine"]["cycle"] == "two-stroke"
    assert needle.load_case(CSV)["engine"]["cycle"] == "four-stroke"


def test_a_bare_csv_table_needs_a_speed():
    case = needle.load_case(CSV)
    assert message(lambda: needle.kinematics(case)) == \
        "rpm=None: " + CSV + " is a bare CSV lift table with no [engine] speed_rpm; give rpm="
    assert message(lambda: needle.overspeed(case)) == \
        CSV + " is a bare CSV lift table with no [engine] speed_rpm; set case['engine']['speed_rpm']"
    at_1000 = needle.kinematics(case, rpm=1000)
    case["engine"]["speed_rpm"] = 1000
    assert same(needle.kinematics(case), at_1000)


# needle.Scene: a case bound once, run many times (issue 52).

def test_a_scene_runs_what_the_functions_run():
    case = needle.load_case(EXAMPLE1)
    scene = needle.Scene(case)
    assert (scene.path, scene.speed_rpm) == (EXAMPLE1, 125)
    assert scene.title.startswith("Basu Example 1")
    for rpm in (125, 300, 700):
        assert same(scene.simulate(rpm=rpm), needle.simulate(case, rpm=rpm)), rpm
    # And what the command runs at that speed (the scene takes the keyword, not its own speed).
    at_700 = scene.simulate(rpm=700)
    cli = json.loads(subprocess.run([BINARY, "simulate", EXAMPLE1, "--rpm", "700", "--json"],
                                    capture_output=True, text=True).stdout)
    assert at_700["speed_rpm"] == 700
    for key in ("max_lift_mm", "min_contact_force_during_lift_N", "liftoff", "episodes"):
        assert at_700[key] == cli[key], key
    assert same(scene.check(), needle.check(case))
    assert same(scene.kinematics(step_deg=1), needle.kinematics(case, step_deg=1))
    assert same(scene.overspeed(from_rpm=600, to_rpm=700),
                needle.overspeed(case, from_rpm=600, to_rpm=700))
    # A scene is a case: every function of a case takes one.
    assert same(needle.simulate(scene, rpm=300), scene.simulate(rpm=300))


def test_a_scene_is_a_snapshot_of_its_case():
    case = needle.load_case(EXAMPLE1)
    scene = needle.Scene(case)
    before = scene.simulate(rpm=600)
    case["spring"]["preload_kgf"] = 300
    assert same(scene.simulate(rpm=600), before)
    weak = needle.simulate(case, rpm=600)
    assert not same(weak, before)
    assert same(needle.Scene(case).simulate(rpm=600), weak)


def test_a_scene_names_its_keywords_and_refuses_what_cannot_be_bound():
    scene = needle.Scene(EXAMPLE1)
    assert message(lambda: scene.simulate(rpm=-5)) == message(lambda: needle.simulate(EXAMPLE1, rpm=-5))
    assert message(lambda: scene.simulate(method="rk4")) == \
        message(lambda: needle.simulate(EXAMPLE1, method="rk4"))
    assert message(lambda: needle.kinematics(scene, spline="pchip")) == \
        "kinematics: spline= needs a case; a needle.Scene is bound with its own"
    # A spline the table has too few points for names the keyword, as the function always did.
    small = {"engine": {"speed_rpm": 400}, "lift": {"crank_deg": [0, 10, 20], "lift_mm": [0, 1, 0]}}
    assert message(lambda: needle.kinematics(small, spline="quintic")).startswith(
        "<dict>: spline='quintic': ")
    # A case whose ramps the model refuses is bound all the same: its kinematics run, and what
    # runs the dynamics is refused naming [train] ramp (issue 52's review: binding once must not
    # refuse a table the kinematics always gave).
    data = data_of(EXAMPLE1)
    data["train"]["play_mm"] = 9.0
    refused = needle.Scene(data)
    assert refused.kinematics()["exit_status"] == 0
    assert needle.kinematics(EXAMPLE1, spline="clamped")["exit_status"] == 0
    for run in (lambda: refused.simulate(), lambda: refused.check(), lambda: needle.simulate(data)):
        assert message(run).startswith("<dict>: [train] ramp: ")
    # Keywords are checked before the case is bound, as the functions always did.
    unbindable = data_of(EXAMPLE1)
    unbindable["lift"]["breaks_deg"] = [100.0]  # read, but refused when the law is built
    assert message(lambda: needle.simulate(unbindable)).startswith("<dict>: [lift] breaks: ")
    assert message(lambda: needle.simulate(unbindable, rpm=-5)).startswith("rpm=-5: ")
    bare = needle.Scene(CSV)
    assert message(lambda: bare.simulate()) == \
        "rpm=None: " + CSV + " is a bare CSV lift table with no [engine] speed_rpm; give rpm="
    # A method's unknown keyword or extra argument is one line naming the method and its
    # keywords (issue 51's trial: pybind11's multi-line list of signatures).
    with pytest.raises(TypeError) as e:
        scene.check(foo=1)
    assert str(e.value) == "Scene.check() got an unexpected keyword argument 'foo'; expected one of rpm"
    with pytest.raises(TypeError) as e:
        scene.kinematics(spline="pchip")
    assert str(e.value) == ("Scene.kinematics() got an unexpected keyword argument 'spline'; "
                            "expected one of rpm, step_deg")
    with pytest.raises(TypeError) as e:
        scene.simulate(400)
    assert str(e.value) == ("Scene.simulate() takes no positional arguments, got 1; give rpm, "
                            "method, rtol, dynamic, series, grid_deg by keyword")
    assert scene.simulate(rpm=400)["speed_rpm"] == 400


# NumPy.

def test_no_numpy_no_import(tmp_path):
    fake = tmp_path / "numpy"
    fake.mkdir()
    (fake / "__init__.py").write_text("raise ModuleNotFoundError(\"No module named 'numpy'\")\n")
    env = dict(os.environ,
               PYTHONPATH=os.pathsep.join([str(tmp_path), os.path.dirname(needle.__file__)]))
    p = subprocess.run([sys.executable, "-c", "import needle"], capture_output=True, text=True,
                       env=env)
    assert p.returncode != 0
    assert p.stderr.strip().splitlines()[-1] == (
        "ImportError: the needle module needs NumPy (its results hold NumPy arrays), and this "
        "Python has none: apt-get install python3-numpy, or pip install numpy "
        "(ModuleNotFoundError: No module named 'numpy')")


# needle.size: the command's JSON object, the [sizing] section set like any other.

def test_size_sizes_a_case_with_a_sizing_section_as_the_command_does():
    case = needle.load_case(os.path.join(ROOT, "cases", "basu-example2.toml"))
    plain = needle.size(case)
    assert plain["pass"] is False and plain["exit_status"] == 1
    assert "reaches the spring fatigue safety factor (Goodman) of at least 1.50" in plain["no_fit"]
    case["sizing"] = {"max_outer_diameter_mm": 52}
    r = needle.size(case)
    assert r["pass"] is True and r["exit_status"] == 0
    assert (r["spring"]["wire_mm"], r["spring"]["coil_mm"], r["spring"]["active_coils"]) == \
        (8.0, 41.0, 3.0)
    assert r["check"]["pass"] is True
    assert r["spring"]["mass_kg"] < r["case_spring_mass_kg"]
    with pytest.raises(needle.CaseError):
        case["sizing"] = {"max_index": 25}
