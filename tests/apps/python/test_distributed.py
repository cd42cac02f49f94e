"""needle.distributed on a local Dask cluster of 2 worker processes on the loopback interface:
the distributed study is `needle tolerance`'s, bit for bit; a study interrupted and started
again computes only the missing shards; a worker killed while it computes costs nothing but
time; a scheduler that does not answer is one line and exit 2. Run by ctest with
PYTHONPATH=build/python and NEEDLE_BINARY=build/needle."""
import glob
import json
import os
import signal
import subprocess
import sys
import tempfile
import time

import pytest

import needle

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
BINARY = os.environ.get("NEEDLE_BINARY", os.path.join(ROOT, "build", "needle"))
# Basu's Example 1 with its lift error on independent points (lift_correlation_deg = 0; the
# default is a smooth error, which no sample refuses): 0.1 s a sample, and 6 of these 40 are
# refused by the model (counted samples, "case refused").
EXAMPLE1 = os.path.join(tempfile.mkdtemp(prefix="needle-distributed-"),
                        "basu-example1-independent.toml")
with open(os.path.join(ROOT, "cases", "basu-example1.toml")) as f, open(EXAMPLE1, "w") as g:
    g.write(f.read() + "\n[tolerance]\nlift_correlation_deg = 0\n")
SAMPLES, SEED, SHARD = 40, 1, 2
TIMING = ("seconds", "seconds_per_sample", "threads")


@pytest.fixture(scope="module")
def cluster():
    try:
        from distributed import Client, LocalCluster
    except ImportError as e:
        pytest.fail(f"Dask's distributed is missing for {sys.executable} ({e}): "
                    "bash scripts/install-deps.sh installs python3-distributed")
    c = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                     dashboard_address=":0")
    client = Client(c)
    yield c.scheduler_address, client
    client.close()
    c.close()


def cli_json(case, samples, seed):
    p = subprocess.run([BINARY, "tolerance", case, "--samples", str(samples), "--seed", str(seed),
                        "--threads", "2", "--json"], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    return json.loads(p.stdout)


@pytest.fixture(scope="module")
def example1_reference():
    return cli_json(EXAMPLE1, SAMPLES, SEED)


def study_args(case, out, scheduler, samples=SAMPLES, seed=SEED, shard=SHARD):
    return [sys.executable, "-m", "needle.distributed", "tolerance", case, "--samples",
            str(samples), "--seed", str(seed), "--out", str(out), "--scheduler", scheduler,
            "--shard-size", str(shard), "--json", "--quiet"]


def run_study(*args):
    p = subprocess.run(study_args(*args), capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    return json.loads(p.stdout)


def statistics(j):
    """The study without the keys that time it (and the distributed run's own)."""
    return {k: v for k, v in j.items() if k not in TIMING + ("distributed",)}


def shard_files(out):
    return sorted(glob.glob(os.path.join(str(out), "shards", "tolerance-*.npz")))


def wait_for_shards(out, count, process, limit_s=120):
    end = time.monotonic() + limit_s
    while len(shard_files(out)) < count:
        assert process.poll() is None, process.communicate()
        assert time.monotonic() < end, "no shards written"
        time.sleep(0.01)


def test_the_distributed_study_is_needle_tolerance(cluster, example1_reference, tmp_path):
    address, _ = cluster
    j = run_study(EXAMPLE1, tmp_path / "study", address)
    assert example1_reference["failure_by_item"]["case refused"] == 0.15  # refused, counted
    assert statistics(j) == statistics(example1_reference)
    d = j["distributed"]
    assert d["shards"] == SAMPLES // SHARD and d["resumed_shards"] == []
    assert d["computed_shards"] == [[k, SHARD] for k in range(0, SAMPLES, SHARD)]
    assert d["worker_threads"] == 2
    assert len(shard_files(tmp_path / "study")) == SAMPLES // SHARD
    with open(tmp_path / "study" / "tolerance.json") as f:
        assert json.load(f) == j


def test_a_case_with_a_csv_table_is_shipped_with_it(cluster, tmp_path):
    # The case's table travels with it: the workers read a copy of their own.
    address, _ = cluster
    case = os.path.join(ROOT, "cases", "measured-cycloidal.toml")
    j = run_study(case, tmp_path / "study", address, 20, 5, 5)
    assert statistics(j) == statistics(cli_json(case, 20, 5))


def test_an_interrupted_study_computes_only_the_missing_shards(cluster, example1_reference,
                                                               tmp_path):
    address, _ = cluster
    out = tmp_path / "study"
    p = subprocess.Popen(study_args(EXAMPLE1, out, address), stdout=subprocess.DEVNULL,
                         stderr=subprocess.DEVNULL)
    wait_for_shards(out, 4, p)
    p.send_signal(signal.SIGKILL)
    p.wait()
    before = {f: os.stat(f).st_mtime_ns for f in shard_files(out)}
    assert 4 <= len(before) < SAMPLES // SHARD, "the study was not interrupted"
    j = run_study(EXAMPLE1, out, address)
    written = {int(os.path.basename(f).split("-")[1]) for f in before}
    d = j["distributed"]
    assert d["resumed_shards"] == [[k, SHARD] for k in sorted(written)]
    assert d["computed_shards"] == [[k, SHARD] for k in range(0, SAMPLES, SHARD)
                                    if k not in written]
    for f, mtime in before.items():
        assert os.stat(f).st_mtime_ns == mtime, f"{f} was written again"
    assert statistics(j) == statistics(example1_reference)


def test_a_killed_worker_costs_only_time(cluster, example1_reference, tmp_path):
    address, client = cluster
    out = tmp_path / "study"
    p = subprocess.Popen(study_args(EXAMPLE1, out, address), stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    wait_for_shards(out, 2, p)
    pids = client.run(os.getpid)
    assert len(pids) == 2
    # The worker's own process (its nanny starts another); both are computing shards now.
    victim = sorted(pids.values())[0]
    assert p.poll() is None and len(shard_files(out)) < SAMPLES // SHARD
    os.kill(victim, signal.SIGKILL)
    stdout, stderr = p.communicate(timeout=300)
    assert p.returncode == 0, stderr
    j = json.loads(stdout)
    assert statistics(j) == statistics(example1_reference)
    assert sorted(k for k, _ in j["distributed"]["computed_shards"]) == list(
        range(0, SAMPLES, SHARD))
    client.wait_for_workers(2, timeout=60)
    assert victim not in client.run(os.getpid).values()


def test_a_scheduler_that_does_not_answer_is_one_line_and_exit_2(tmp_path):
    # Port 9 (discard) on the loopback: nothing listens. The connect timeout is 2 s; with
    # Python's start, the probe sample and Dask's import the whole refusal takes under 15 s.
    start = time.monotonic()
    p = subprocess.run(study_args(EXAMPLE1, tmp_path / "out", "tcp://127.0.0.1:9") +
                       ["--connect-timeout", "2"], capture_output=True, text=True, timeout=60)
    elapsed = time.monotonic() - start
    assert p.returncode == 2
    assert p.stdout == ""
    lines = p.stderr.splitlines()
    assert len(lines) == 1, p.stderr
    assert lines[0].startswith("needle: --scheduler tcp://127.0.0.1:9: no Dask scheduler "
                               "answered within 2 s ("), lines[0]
    assert 2.0 <= elapsed < 15.0
    assert not os.path.exists(tmp_path / "out"), "something was written"


def test_a_bad_case_is_refused_before_anything_is_sent(tmp_path):
    case = tmp_path / "bad.toml"
    with open(EXAMPLE1) as f:
        case.write_text(f.read().replace("mass_kg = ", "mass_kg = -"))
    p = subprocess.run(study_args(str(case), tmp_path / "out", "tcp://127.0.0.1:9"),
                       capture_output=True, text=True, timeout=60)
    cli = subprocess.run([BINARY, "tolerance", str(case)], capture_output=True, text=True)
    assert cli.returncode == 2 and p.returncode == 2
    assert p.stderr == cli.stderr and len(p.stderr.splitlines()) == 1
    assert "mass_kg" in p.stderr
    assert not os.path.exists(tmp_path / "out")


def test_a_folder_of_another_study_is_refused(cluster, tmp_path):
    address, _ = cluster
    case = os.path.join(ROOT, "cases", "measured-cycloidal.toml")
    run_study(case, tmp_path / "study", address, 4, 5, 2)
    p = subprocess.run(study_args(case, tmp_path / "study", address, 4, 6, 2),
                       capture_output=True, text=True, timeout=60)
    assert p.returncode == 2
    assert p.stderr == (f"needle: --out: {tmp_path / 'study' / 'shards'} holds shards of another "
                        f"study (tolerance-0000000000-0000002.npz: case {case}, seed 5); "
                        "expected a new folder or this study's\n")


def test_the_package_is_the_module():
    # `import needle` is the compiled module; needle.distributed is found beside it.
    import needle.distributed as nd
    assert nd.needle is needle
    assert os.path.dirname(os.path.dirname(nd.__file__)) == os.path.dirname(needle.__file__)
    assert needle.__version__.count(".") == 2


def test_shard_sizes_keep_the_scheduler_under_one_percent():
    from needle.distributed import choose_shard_size
    # 10 ms a task, 0.1 s a sample: 10 samples are 1 s, of which the 10 ms are 1 %.
    assert choose_shard_size(10 ** 6, 64, 0.1, 0.01) == 3000  # 5 minutes of one core at most
    assert choose_shard_size(40, 2, 0.1, 0.01) == 10
    assert choose_shard_size(40, 64, 0.1, 0.01) == 10  # never under the 1 % floor
    assert choose_shard_size(5, 64, 0.1, 0.01) == 5


def test_a_map_is_the_check_at_each_grid_point(cluster, tmp_path):
    # Speeds × preloads × masses of Basu's cam No. 4 with a light spring: each point is what
    # `needle check` says of the case with those values (pass, n_dyn, n_qs).
    address, _ = cluster
    case = os.path.join(ROOT, "cases", "basu-cam4-light-spring.toml")
    p = subprocess.run([sys.executable, "-m", "needle.distributed", "map", case, "--speeds",
                        "300,500", "--set", "spring.preload_N=250,400", "--set",
                        "needle.mass_kg=1.0,1.5", "--out", str(tmp_path / "map"), "--scheduler",
                        address, "--chunk", "3", "--json", "--quiet"],
                       capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    m = json.loads(p.stdout)
    assert m["grid"] == {"engine.speed_rpm": [300, 500], "spring.preload_N": [250, 400],
                         "needle.mass_kg": [1.0, 1.5]}
    assert len(m["points"]) == 8 and m["distributed"]["computed_chunks"] == [[0, 3], [3, 3],
                                                                            [6, 2]]
    verdicts = set()
    for i, point in enumerate(m["points"]):
        d = needle.load_case(case).to_dict()
        for key in m["grid"]:
            section, name = key.split(".")
            d[section][name] = point[key]
        path = tmp_path / f"point{i}.toml"
        path.write_text(needle.case_text(d))
        c = subprocess.run([BINARY, "check", str(path), "--json"], capture_output=True, text=True,
                           cwd=tmp_path)
        assert c.returncode in (0, 1), c.stderr
        j = json.loads(c.stdout)
        assert point["pass"] == (c.returncode == 0), (point, j["failing"])
        assert point["n_dyn_rpm"] == j["overspeed"]["liftoff_rpm_dynamic"]
        assert point["n_qs_rpm"] == j["overspeed"]["liftoff_rpm_quasi_static"]
        verdicts.add(point["pass"])
    assert verdicts == {True, False}  # the grid crosses the verdict


def test_shards_reduce_to_the_study():
    # Without Dask: shards [0, 5) and [5, 12) of Example 1, gathered, are the 12-sample study;
    # sample 10, refused by the model, keeps its place and its reason, and has no outputs.
    path = EXAMPLE1
    text = open(path).read()
    shards = [needle.tolerance_shard(text, path=path, seed=1, first_sample=a, samples=n)
              for a, n in ((0, 5), (5, 7))]
    assert [s["inputs"].shape[0] for s in shards] == [5, 7]
    assert shards[1]["refused"][5].startswith(path + ": ")
    assert not shards[1]["output_present"][5].any() and shards[1]["output_present"][4].all()
    whole = needle.tolerance(path, samples=12, seed=1, threads=1)
    assert whole["sample_results"][10]["refused"] == shards[1]["refused"][5]
    gathered = needle.tolerance_reduce(path, shards, seed=1, threads=1, seconds=whole["seconds"])
    assert gathered == whole
    # The shards must tile the study (issue 51's trial: a shard twice, a gap, the order or
    # another first_sample were reduced as if they did, samples miscounted or mislabelled).
    for bad, where in ((shards[::-1], "shards\\[0\\]: starts at sample 5; expected 0"),
                       ([shards[0], shards[0]], "shards\\[1\\]: starts at sample 0; expected 5")):
        with pytest.raises(needle.CaseError, match=where):
            needle.tolerance_reduce(path, bad, seed=1)
    with pytest.raises(needle.CaseError, match="shards\\[0\\]: starts at sample 5; expected 3 "
                       "\\(the shards in sample order, each where the last ended, the first at "
                       "first_sample=3\\)"):
        needle.tolerance_reduce(path, shards[1:], seed=1, first_sample=3)
    tail = needle.tolerance_reduce(path, shards[1:], seed=1, first_sample=5)
    assert tail["sample_results"] == whole["sample_results"][5:]
    with pytest.raises(needle.CaseError, match="needs at least one sample"):
        needle.tolerance_reduce(path, [], seed=1)


def test_shards_that_are_not_the_studys_are_refused_naming_why():
    # Issue 51: a dict without a shard's keys was a raw KeyError; shards of seed 1 reduced
    # with seed=2 were labelled seed 2.
    path = EXAMPLE1
    shard = needle.tolerance_shard(open(path).read(), path=path, seed=1, first_sample=0,
                                   samples=2)
    assert shard["seed"] == 1
    keys = ("expected the keys tolerance_shard writes: failing, first_sample, input_keys, "
            "input_present, inputs, output_keys, outputs, output_present, pass, refused, "
            "samples, seed (and case_digest, and run_shard's seconds, worker)")

    def refusal(shards, seed=1):
        with pytest.raises(needle.CaseError) as e:
            needle.tolerance_reduce(path, shards, seed=seed)
        assert isinstance(e.value, ValueError)
        return str(e.value)
    assert refusal([{"bogus": 1}]) == "shards[0]: unknown key 'bogus'; " + keys
    assert refusal([shard, {k: v for k, v in shard.items() if k != "pass"}]) == \
        "shards[1]: no key 'pass'; " + keys
    assert refusal([shard, 3]) == "shards[1]: expected a dict of tolerance_shard, got an int"
    assert refusal([dict(shard, samples="2")]) == \
        "shards[0]['samples']: expected what tolerance_shard writes there, got a str"
    assert refusal([shard], seed=2) == \
        "seed=2: shards[0] was made with seed=1; expected the seed its shards were made with"
    # Shards of another case (issue 51's trial: reduced without a word). The same case given as
    # its path, as a needle.Case or as the dict load_case made of it is the shards' case.
    other = needle.load_case(path)
    other["spring"]["preload_kgf"] = 800
    digest = shard["case_digest"]
    assert len(digest) == 16
    with pytest.raises(needle.CaseError) as e:
        needle.tolerance_reduce(other, [shard], seed=1)
    assert str(e.value) == (
        f"shards[0] was made from another case (case_digest {digest}, this case's "
        f"{needle.tolerance_shard(needle.case_text(other), path=path, seed=1, first_sample=0, samples=1)['case_digest']}"
        "); reduce shards with the case they were made from")
    same = needle.load_case(path)
    for source in (path, same, same.to_dict()):
        assert needle.tolerance_reduce(source, [shard], seed=1)["samples"] == 2
    # A file written with an inline table and comments is the same case as its dict (the
    # digest is of the case as load_case holds it, not of the text's layout).
    inline = os.path.join(os.path.dirname(path), "inline.toml")
    with open(path) as f, open(inline, "w") as g:
        g.write("# inline\n" + f.read().replace(
            '[engine]\nspeed_rpm = 125\ncycle = "four-stroke"\n',
            'engine = { speed_rpm = 125, cycle = "four-stroke" }  # one line\n'))
    assert "engine = {" in open(inline).read()
    inline_shard = needle.tolerance_shard(open(inline).read(), path=inline, seed=1,
                                          first_sample=0, samples=1)
    assert inline_shard["case_digest"] == digest
    assert inline_shard["case_digest"] == needle.tolerance_shard(
        needle.case_text(inline), path=inline, seed=1, first_sample=0,
        samples=1)["case_digest"]
    assert needle.tolerance_reduce(inline, [inline_shard], seed=1)["samples"] == 1
    # run_shard's additions are a shard's too.
    assert needle.tolerance_reduce(path, [dict(shard, seconds=0.1, worker="w:1")],
                                   seed=1)["samples"] == 2


def test_the_documented_commands_on_the_loopback(tmp_path):
    # docs/distributed.md's set-up: dask-scheduler (here without needle on its path) and
    # dask-worker with 2 processes; a scheduler with no worker yet is one line and exit 2.
    from distributed import Client
    plain = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    scheduler_file = tmp_path / "scheduler.json"
    scheduler = subprocess.Popen(
        [sys.executable, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1", "--port",
         "0", "--dashboard-address", ":0", "--scheduler-file", str(scheduler_file)], env=plain,
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    worker = None
    try:
        end = time.monotonic() + 60
        while not scheduler_file.exists():
            assert time.monotonic() < end and scheduler.poll() is None, "no scheduler"
            time.sleep(0.05)
        time.sleep(0.2)  # the file written whole
        address = json.loads(scheduler_file.read_text())["address"]
        p = subprocess.run(study_args(EXAMPLE1, tmp_path / "none", address) +
                           ["--connect-timeout", "1"], capture_output=True, text=True, timeout=60)
        assert (p.returncode, p.stderr) == (2, f"needle: --scheduler {address}: the scheduler has "
                                               f"no worker after 1 s (start dask-worker "
                                               f"{address} on the workers' machines)\n")
        worker = subprocess.Popen(
            [sys.executable, "-m", "distributed.cli.dask_worker", address, "--nworkers", "2",
             "--nthreads", "1", "--host", "127.0.0.1"], stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL)
        with Client(address) as client:
            client.wait_for_workers(2, timeout=60)
        case = os.path.join(ROOT, "cases", "measured-cycloidal.toml")
        j = run_study(case, tmp_path / "study", address, 20, 7, 5)
        assert j["distributed"]["worker_threads"] == 2
        assert statistics(j) == statistics(cli_json(case, 20, 7))
    finally:
        for process in (worker, scheduler):
            if process is not None:
                process.terminate()
                process.wait(timeout=60)
