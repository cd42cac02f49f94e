"""needle.distributed: a tolerance study spread over a Dask cluster, resumable shard by shard.

    python3 -m needle.distributed tolerance CASE --samples N --seed S --out DIR \\
        [--scheduler tcp://HOST:8786] [--json]

Each task is a pure function of (case text and the files it names, seed, first sample, count):
a shard of the study, computed by needle.tolerance_shard (the library's samples, as
`needle tolerance --first-sample` computes them). The client writes every finished shard to
DIR/shards/ as it arrives (NumPy .npz, with the case's hash, the seed and the range in its
metadata), gathers the shards in sample order and reduces them once with
needle.tolerance_reduce (the statistics code of `needle tolerance`): the result is the
one-machine study's, bit for bit. Started again with the same arguments it computes only the
shards not yet written. Without --scheduler it starts a local cluster on this machine's cores.
Bad input (the case, an option, a scheduler that does not answer) is one line on stderr and
exit status 2, with nothing sent. docs/distributed.md says how to run it on several machines.
"""

import argparse
import copy
import hashlib
import itertools
import json
import math
import os
import sys
import tempfile
import time
import tomllib

import needle
from needle.cluster import Progress, choose_shard_size, connect, task_overhead  # noqa: F401
from needle.cluster import _scheduler_has_bokeh
from needle.shards import (SHARD_PREFIX, BadInput, TaskFailed, _publish,  # noqa: F401
                           case_bundle, existing_shards, missing_ranges, read_shard, run_shard,
                           shard_name, split, write_shard)


# The study.


def tolerance(args):
    """The study as `python3 -m needle.distributed tolerance` runs it; returns the JSON object."""
    wall = time.perf_counter()
    bundle = case_bundle(args.case)
    # The case as the workers will take it: a case refused here is refused before anything is
    # sent; the sample's time is the cost the task size is chosen from.
    probe = time.perf_counter()
    try:
        run_shard(bundle, args.seed, args.first_sample, 1)
    except needle.CaseError as e:
        raise BadInput(str(e)) from None
    seconds_per_sample = time.perf_counter() - probe
    shards_dir = os.path.join(args.out, "shards")
    study = {"case": args.case, "case_sha256": bundle["sha256"], "seed": args.seed,
             "first_sample": args.first_sample, "end": args.first_sample + args.samples}
    have = existing_shards(shards_dir, study) if os.path.isdir(shards_dir) else {}
    gaps = missing_ranges(study["first_sample"], study["end"], have)

    # Nothing is written before the scheduler answers.
    client, cluster = connect(args.scheduler, args.workers, args.connect_timeout)
    try:
        try:
            os.makedirs(shards_dir, exist_ok=True)
        except OSError as e:
            raise BadInput(f"--out: {args.out}: cannot make the folder ({e.strerror})") from None
        info = client.scheduler_info()
        slots = sum(w.get("nthreads", 1) for w in info["workers"].values()) or 1
        dashboard = "dashboard" in info.get("services", {}) and _scheduler_has_bokeh(client)
        if dashboard and not args.quiet:
            print(f"dashboard: {client.dashboard_link}", file=sys.stderr)
        overhead = task_overhead(client)
        size = args.shard_size or choose_shard_size(args.samples, slots, seconds_per_sample,
                                                    overhead)
        tasks = split(gaps, size)
        progress = Progress(len(tasks), sum(n for _, n in tasks), not args.quiet)
        computed, task_seconds = [], 0.0
        submitted = time.perf_counter()
        if tasks:
            from distributed import as_completed

            futures = [client.submit(run_shard, bundle, args.seed, first, n, pure=True,
                                     key=f"needle-tolerance-{bundle['sha256'][:12]}-"
                                         f"{args.seed}-{first}-{n}")
                       for first, n in tasks]
            for future in as_completed(futures):
                try:
                    shard = future.result()
                except Exception as e:  # the cluster gave up on a task (a worker died thrice)
                    first, n = next(t for t, f in zip(tasks, futures) if f is future)
                    why = (str(e).splitlines() or [""])[0]
                    raise TaskFailed(f"shard [{first}, {first + n}) failed on the cluster "
                                     f"({type(e).__name__}: {why}); the {len(computed)} shards "
                                     f"written in {shards_dir} are kept: the same command "
                                     "resumes") from None
                meta = {"case": args.case, "case_sha256": bundle["sha256"], "seed": args.seed,
                        "first_sample": shard["first_sample"], "samples": shard["samples"],
                        "needle_version": needle.__version__, "worker": shard["worker"]}
                write_shard(shards_dir, meta, shard)
                computed.append([shard["first_sample"], shard["samples"]])
                task_seconds += shard["seconds"]
                progress.update(shard["samples"])
                future.release()
        compute_wall = time.perf_counter() - submitted
    finally:
        client.close()
        if cluster is not None:
            cluster.close()

    gathered = existing_shards(shards_dir, study)
    if missing_ranges(study["first_sample"], study["end"], gathered):
        raise RuntimeError("shards are missing after the study: "
                           f"{missing_ranges(study['first_sample'], study['end'], gathered)}")
    seconds = time.perf_counter() - wall
    result = needle.tolerance_reduce(args.case, [gathered[k] for k in sorted(gathered)],
                                     seed=args.seed, first_sample=args.first_sample,
                                     threads=slots, seconds=seconds)
    result.pop("columns", None)
    result.pop("exit_status", None)
    computed.sort()
    result["distributed"] = {
        "scheduler": args.scheduler or "local",
        "worker_threads": slots,
        "shard_size": size,
        "shards": len(gathered),
        "computed_shards": computed,
        "resumed_shards": sorted([k, have[k]["samples"]] for k in have),
        "probe_seconds_per_sample": seconds_per_sample,
        "task_overhead_s": overhead,
        "task_seconds": task_seconds,
        # Samples per second from the tasks' submission to the last shard written (the
        # cluster's start, the probe and the reduction aside), and over the whole command.
        "compute_seconds": compute_wall,
        "samples_per_second": (sum(n for _, n in computed) / compute_wall
                               if computed else None),
        "samples_per_second_overall": (sum(n for _, n in computed) / seconds
                                       if computed else None),
        "shards_folder": shards_dir,
    }
    with open(os.path.join(args.out, "tolerance.json"), "w") as f:
        json.dump(result, f, indent=2)
    return result


# Maps: the nominal check on a grid of speeds × case keys.

#: The scatter of a map's points: none (the sample is the nominal case).
NO_SCATTER = {"lift_mm": 0.0, "lift_correlation_deg": 0.0, "mass_percent": 0.0,
              "preload_percent": 0.0, "rate_percent": 0.0, "stiffness_percent": 0.0,
              "play_mm": 0.0, "speed_percent": 0.0}


def _value(text, option):
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        raise BadInput(f"{option}: {text!r}: expected a number, true/false or a quoted "
                       "string") from None


def grid_axes(args):
    """[(key, values)]: the speeds first, then each --set SECTION.KEY=V1,V2,… in order."""
    axes = [("engine.speed_rpm", [_value(v, "--speeds") for v in args.speeds.split(",")])]
    for item in args.set or []:
        key, _, values = item.partition("=")
        section, _, name = key.partition(".")
        if not (section and name and values) or "." in name:
            raise BadInput(f"--set {item!r}: expected SECTION.KEY=V1,V2,… "
                           "(needle.mass_kg=1.2,1.4)")
        if key in (k for k, _ in axes):
            raise BadInput(f"--set {item!r}: {key} is given twice")
        axes.append((key, [_value(v, f"--set {key}") for v in values.split(",")]))
    return axes


def map_bundles(args, base):
    """One bundle a grid point: the case with the point's values and no scatter, validated
    here (a value the case refuses is refused before anything is sent)."""
    axes = grid_axes(args)
    data = needle.load_case(args.case).to_dict()
    bundles, points = [], []
    for values in itertools.product(*[v for _, v in axes]):
        d = copy.deepcopy(data)
        point = {}
        for (key, _), v in zip(axes, values):
            section, name = key.split(".")
            d.setdefault(section, {})[name] = v
            point[key] = v
        d["tolerance"] = dict(NO_SCATTER)
        try:
            text = needle.case_text(needle.load_case(d, name=args.case))
        except needle.CaseError as e:
            raise BadInput(f"{e} (grid point {point})") from None
        digest = hashlib.sha256(text.encode() + base["sha256"].encode()).hexdigest()
        bundles.append({"path": args.case, "text": text, "files": base["files"],
                        "sha256": digest})
        points.append(point)
    return axes, points, bundles


def run_points(bundles):
    """One task of a map: each point's nominal check, as a one-sample shard."""
    return [run_shard(b, 1, 0, 1) for b in bundles]


def point_result(point, shard):
    out = dict(zip(shard["output_keys"], shard["outputs"][0].tolist()))
    present = dict(zip(shard["output_keys"], shard["output_present"][0].tolist()))
    value = {k: (v if present[k] and math.isfinite(v) else None) for k, v in out.items()}
    return dict(point, **{
        "pass": bool(shard["pass"][0]),
        "failing": shard["failing"][0],
        "refused": shard["refused"][0],
        "n_dyn_rpm": value.get("overspeed.liftoff_rpm_dynamic"),
        "n_qs_rpm": value.get("spring.liftoff_rpm_quasi_static"),
        "outputs": value,
    })


def speed_map(args):
    """The map as `python3 -m needle.distributed map` runs it; returns its JSON object."""
    wall = time.perf_counter()
    base = case_bundle(args.case)
    axes, points, bundles = map_bundles(args, base)
    grid_hash = hashlib.sha256("".join(b["sha256"] for b in bundles).encode()).hexdigest()
    probe = time.perf_counter()
    try:
        run_shard(bundles[0], 1, 0, 1)
    except needle.CaseError as e:
        raise BadInput(str(e)) from None
    seconds_per_point = time.perf_counter() - probe
    folder = os.path.join(args.out, "points")
    have = {}
    if os.path.isdir(folder):
        for name in os.listdir(folder):
            if name.startswith("points-") and name.endswith(".json"):
                try:
                    with open(os.path.join(folder, name)) as f:
                        chunk = json.load(f)
                except (OSError, ValueError):
                    continue
                if chunk.get("grid_sha256") != grid_hash:
                    raise BadInput(f"--out: {folder} holds points of another map ({name}); "
                                   "expected a new folder or this map's")
                have[chunk["first"]] = dict(chunk, samples=len(chunk["points"]))
    gaps = missing_ranges(0, len(points), have)
    client, cluster = connect(args.scheduler, args.workers, args.connect_timeout)
    try:
        os.makedirs(folder, exist_ok=True)
        info = client.scheduler_info()
        slots = sum(w.get("nthreads", 1) for w in info["workers"].values()) or 1
        overhead = task_overhead(client)
        size = args.chunk or choose_shard_size(len(points), slots, seconds_per_point, overhead)
        tasks = split(gaps, size)
        progress = Progress(len(tasks), sum(n for _, n in tasks), not args.quiet,
                            ("map", "chunks", "points"))
        computed = []
        if tasks:
            from distributed import as_completed

            futures = {client.submit(run_points, bundles[a:a + n], pure=True,
                                     key=f"needle-map-{grid_hash[:12]}-{a}-{n}"): (a, n)
                       for a, n in tasks}
            for future in as_completed(list(futures)):
                first, n = futures[future]
                try:
                    shards = future.result()
                except Exception as e:
                    why = (str(e).splitlines() or [""])[0]
                    raise TaskFailed(f"points [{first}, {first + n}) failed on the cluster "
                                     f"({type(e).__name__}: {why}); the points written in "
                                     f"{folder} are kept: the same command resumes") from None
                chunk = {"grid_sha256": grid_hash, "first": first,
                         "points": [point_result(points[first + i], sh)
                                    for i, sh in enumerate(shards)]}
                fd, tmp = tempfile.mkstemp(dir=folder, suffix=".part")
                with os.fdopen(fd, "w") as f:
                    json.dump(chunk, f)
                _publish(tmp, os.path.join(folder, f"points-{first:07d}-{n:05d}.json"))
                have[first] = dict(chunk, samples=n)
                computed.append([first, n])
                progress.update(n)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    results = []
    for first in sorted(have):
        results.extend(have[first]["points"])
    result = {"case": args.case, "grid": dict(axes), "points": results,
              "seconds": time.perf_counter() - wall,
              "distributed": {"scheduler": args.scheduler or "local", "worker_threads": slots,
                              "chunk": size, "computed_chunks": sorted(computed),
                              "probe_seconds_per_point": seconds_per_point,
                              "task_overhead_s": overhead, "out": args.out}}
    with open(os.path.join(args.out, "map.json"), "w") as f:
        json.dump(result, f, indent=2)
    return result


def _map_summary(r):
    keys = list(r["grid"])
    lines = ["  ".join(f"{k:>18}" for k in keys) +
             f"  {'n_dyn (rpm)':>12}  {'n_qs (rpm)':>11}  verdict"]
    for p in r["points"]:
        fmt = lambda v: "-" if v is None else f"{v:.1f}"  # noqa: E731
        verdict = "pass" if p["pass"] else "FAIL: " + ", ".join(p["failing"])
        lines.append("  ".join(f"{p[k]!s:>18}" for k in keys) +
                     f"  {fmt(p['n_dyn_rpm']):>12}  {fmt(p['n_qs_rpm']):>11}  {verdict}")
    lines.append(f"map: {os.path.join(r['distributed']['out'], 'map.json')}")
    return "\n".join(lines)


def _summary(r):
    d = r["distributed"]
    lines = [f"{r['case']}: {r['samples']} samples, seed {r['seed']}, {d['shards']} shards of "
             f"{d['shard_size']} ({len(d['computed_shards'])} computed, "
             f"{len(d['resumed_shards'])} already written) on {d['worker_threads']} worker "
             f"threads, {r['seconds']:.2f} s",
             f"the check fails in {100 * r['failure_probability']:.2f} % of the samples "
             f"(95 % {100 * r['failure_probability_95'][0]:.2f} .. "
             f"{100 * r['failure_probability_95'][1]:.2f} %)"]
    for item, p in r["failure_by_item"].items():
        first = next((s["refused"] for s in r["sample_results"] if s.get("refused")), None)
        lines.append(f"  {item}: {100 * p:.2f} %" +
                     (f" (the first: {first})" if item == "case refused" and first else ""))
    for key in ("overspeed.liftoff_rpm_dynamic", "spring.liftoff_rpm_quasi_static"):
        dist = r["distributions"].get(key)
        if dist and dist["count"]:
            lines.append(f"{key}: mean {dist['mean']:.6g}, 5 % {dist['p05']:.6g}, median "
                         f"{dist['p50']:.6g}, 95 % {dist['p95']:.6g}")
    lines.append(f"result: {os.path.join(os.path.dirname(d['shards_folder']), 'tolerance.json')}")
    return "\n".join(lines)


class _Parser(argparse.ArgumentParser):
    """argparse's refusals as one line and exit 2."""

    def error(self, message):
        raise BadInput(message)


def parser():
    p = _Parser(prog="python3 -m needle.distributed",
                                description="needle studies on a Dask cluster")
    sub = p.add_subparsers(dest="command", required=True)
    t = sub.add_parser("tolerance", help="a Monte-Carlo tolerance study (needle tolerance)")
    t.add_argument("case", metavar="CASE", help="case file; its [tolerance] section")
    t.add_argument("--samples", type=int, default=1000, help="number of samples (default 1000)")
    t.add_argument("--seed", type=int, default=1, help="the study's seed (default 1)")
    t.add_argument("--first-sample", type=int, default=0, help="index of the first sample")
    t.add_argument("--out", required=True,
                   help="the study's folder: shards/ as they arrive, tolerance.json at the end")
    t.add_argument("--scheduler", help="a Dask scheduler's address, tcp://HOST:8786 (default: "
                   "a local cluster on this machine's cores)")
    t.add_argument("--workers", type=int, default=0,
                   help="local cluster only: worker processes (default: the cores)")
    t.add_argument("--shard-size", type=int, default=0,
                   help="samples per task (default: from the measured cost per sample, for "
                   "under 1 %% of scheduling overhead)")
    t.add_argument("--connect-timeout", type=float, default=10.0,
                   help="seconds to wait for the scheduler (default 10)")
    t.add_argument("--json", action="store_true",
                   help="print needle tolerance --json's object, plus 'distributed'")
    t.add_argument("--quiet", action="store_true", help="no progress on stderr")
    m = sub.add_parser("map", help="the nominal check on a grid of speeds × case keys")
    m.add_argument("case", metavar="CASE", help="case file")
    m.add_argument("--speeds", required=True, help="crank speeds, rpm: 300,400,500")
    m.add_argument("--set", action="append", metavar="SECTION.KEY=V1,V2",
                   help="a case key's values (repeatable): spring.preload_kgf=150,176")
    m.add_argument("--out", required=True,
                   help="the map's folder: points/ as they arrive, map.json at the end")
    m.add_argument("--scheduler", help="a Dask scheduler's address (default: a local cluster)")
    m.add_argument("--workers", type=int, default=0,
                   help="local cluster only: worker processes (default: the cores)")
    m.add_argument("--chunk", type=int, default=0,
                   help="points per task (default: from the measured cost of one)")
    m.add_argument("--connect-timeout", type=float, default=10.0,
                   help="seconds to wait for the scheduler (default 10)")
    m.add_argument("--json", action="store_true", help="print map.json's object")
    m.add_argument("--quiet", action="store_true", help="no progress on stderr")
    return p


def check_ranges(args):
    if args.command == "map":
        if not 0 <= args.chunk <= 1000000:
            raise BadInput(f"--chunk: expected a number of points in [1, 1000000] (0: chosen), "
                           f"got {args.chunk}")
        args.samples, args.seed, args.first_sample, args.shard_size = 1, 1, 0, 0
    if not 1 <= args.samples <= 1000000:
        raise BadInput(f"--samples: expected a number of samples in [1, 1000000], got "
                       f"{args.samples}")
    if not 0 <= args.seed < 2**64:
        raise BadInput(f"--seed: expected a whole number in [0, 2^64), got {args.seed}")
    if not 0 <= args.first_sample <= 1000000000:
        raise BadInput(f"--first-sample: expected an index in [0, 1000000000], got "
                       f"{args.first_sample}")
    if not 0 <= args.shard_size <= 1000000:
        raise BadInput(f"--shard-size: expected a number of samples in [1, 1000000] (0: "
                       f"chosen), got {args.shard_size}")
    if not 0 <= args.workers <= 1024:
        raise BadInput(f"--workers: expected a number of processes in [1, 1024] (0: the "
                       f"cores), got {args.workers}")
    if not 0 < args.connect_timeout <= 3600:
        raise BadInput(f"--connect-timeout: expected seconds in (0, 3600], got "
                       f"{args.connect_timeout}")


def main(argv=None):
    # The command's own lines are its messages: Dask's loggers (a connect retry, a timeout while
    # closing a client that never had a worker) would add lines of their own to the one line of
    # a refusal, and more of them on a loaded machine. Only their critical records are shown.
    import logging
    logging.getLogger("distributed").setLevel(logging.CRITICAL)
    try:
        args = parser().parse_args(argv)
        check_ranges(args)
        result = tolerance(args) if args.command == "tolerance" else speed_map(args)
    except BadInput as e:
        print(f"needle: {e}", file=sys.stderr)
        return 2
    except TaskFailed as e:
        print(f"needle: {e}", file=sys.stderr)
        return 3
    summary = _summary if args.command == "tolerance" else _map_summary
    print(json.dumps(result, indent=2) if args.json else summary(result))
    return 0


if __name__ == "__main__":
    # Run as the module needle.distributed (not __main__), so that the tasks name their
    # functions by a module the workers can import.
    from needle.distributed import main as _main

    sys.exit(_main())
