#!/usr/bin/python3
"""The figures of docs/distributed.md: a tolerance study's samples per second on 1 and 2 local
Dask workers against `needle tolerance --threads 1/2`, Dask's time per task, the reduction's
time and memory, and the projection to 10^6 samples on 64 cores.

    PYTHONPATH=build/python /usr/bin/python3 scripts/bench_distributed.py \\
        [--case cases/basu-example2.toml] [--samples 100] [--binary build/needle]

Prints a Markdown section (paste it into docs/distributed.md) and, last, one JSON line."""
import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time

import needle
import needle.distributed as nd


def cli_rate(binary, case, samples, threads):
    start = time.perf_counter()
    p = subprocess.run([binary, "tolerance", case, "--samples", str(samples), "--seed", "1",
                        "--threads", str(threads), "--json"], capture_output=True, text=True,
                       check=True)
    wall = time.perf_counter() - start
    return samples / wall, json.loads(p.stdout)


def dask_rate(case, samples, workers, shard):
    with tempfile.TemporaryDirectory() as out:
        start = time.perf_counter()
        p = subprocess.run([sys.executable, "-m", "needle.distributed", "tolerance", case,
                            "--samples", str(samples), "--seed", "1", "--out", out, "--workers",
                            str(workers), "--shard-size", str(shard), "--json", "--quiet"],
                           capture_output=True, text=True, check=True)
        wall = time.perf_counter() - start
    j = json.loads(p.stdout)
    return j["distributed"]["samples_per_second"], j, samples / wall


def noop_overhead(workers, tasks):
    """Dask's round trip of one empty task, and its time per task when `tasks` empty tasks are
    mapped at once, on a local cluster of `workers` processes."""
    from distributed import Client, LocalCluster
    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, host="127.0.0.1",
                      dashboard_address=":0") as cluster, Client(cluster) as client:
        client.submit(nd._noop, -1, pure=False).result()  # warm
        latency = nd.task_overhead(client, rounds=21)
        start = time.perf_counter()
        client.gather(client.map(nd._noop, range(tasks), pure=False))
        per_task = (time.perf_counter() - start) / tasks
    return latency, per_task


def reduce_cost(case, shard, copies):
    """Seconds and peak memory of the client's reduction of `copies` × the shard's samples."""
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    start = time.perf_counter()
    needle.tolerance_reduce(case, [shard] * copies, seed=1)
    seconds = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return seconds, (after - before) * 1024.0


def main():
    a = argparse.ArgumentParser()
    a.add_argument("--case", default="cases/basu-example2.toml")
    a.add_argument("--samples", type=int, default=100)
    a.add_argument("--binary", default="build/needle")
    a.add_argument("--noop-tasks", type=int, default=1000)
    args = a.parse_args()
    shard = max(1, args.samples // 10)
    r = {"case": args.case, "samples": args.samples, "shard_size": shard,
         "load_average": os.getloadavg()[0]}
    r["cli_1"], cli1 = cli_rate(args.binary, args.case, args.samples, 1)
    r["cli_2"], _ = cli_rate(args.binary, args.case, args.samples, 2)
    r["dask_1"], d1, r["dask_1_overall"] = dask_rate(args.case, args.samples, 1, shard)
    r["dask_2"], d2, r["dask_2_overall"] = dask_rate(args.case, args.samples, 2, shard)
    r["seconds_per_sample"] = cli1["seconds"] / args.samples
    r["noop_latency_s"], r["noop_per_task_s"] = noop_overhead(2, args.noop_tasks)
    # The study's own overhead per task: its worker threads' wall time not spent in a task.
    dd = d2["distributed"]
    r["study_overhead_per_task_s"] = (
        (dd["compute_seconds"] * dd["worker_threads"] - dd["task_seconds"]) /
        len(dd["computed_shards"]))
    shard_data = nd.run_shard(nd.case_bundle(args.case), 1, 0, shard)
    copies = max(1, 20000 // shard)
    r["reduce_samples"] = copies * shard
    r["reduce_s"], r["reduce_bytes"] = reduce_cost(args.case, shard_data, copies)

    # The projection: 10^6 samples on 64 cores, one worker process a core.
    n, cores, c = 10 ** 6, 64, r["seconds_per_sample"]
    size = nd.choose_shard_size(n, cores, c, r["noop_latency_s"])
    tasks = -(-n // size)
    compute = n * c / cores
    scheduling = tasks * r["noop_per_task_s"]  # the scheduler's time, serial, at the client
    reduce_s = r["reduce_s"] * n / r["reduce_samples"]
    r["projection"] = {"samples": n, "cores": cores, "shard_size": size, "tasks": tasks,
                       "compute_s": compute, "scheduling_s": scheduling, "reduce_s": reduce_s,
                       "reduce_bytes": r["reduce_bytes"] * n / r["reduce_samples"],
                       "total_s": compute + reduce_s + max(0.0, scheduling - compute)}
    p = r["projection"]
    print(f"Measured with `{' '.join(sys.argv)}` ({args.case}, {args.samples} samples, seed "
          f"1; load average {r['load_average']:.2f} at the start, on this machine's "
          f"{os.cpu_count()} cores):\n")
    print("| run | samples/s, tasks | against the CLI | samples/s, whole command |")
    print("|---|---|---|---|")
    print(f"| `needle tolerance --threads 1` | {r['cli_1']:.2f} | 1 | {r['cli_1']:.2f} |")
    print(f"| `needle tolerance --threads 2` | {r['cli_2']:.2f} | 1 | {r['cli_2']:.2f} |")
    print(f"| `needle.distributed`, 1 local worker, shards of {shard} | {r['dask_1']:.2f} | "
          f"{r['dask_1'] / r['cli_1']:.3f} | {r['dask_1_overall']:.2f} |")
    print(f"| `needle.distributed`, 2 local workers, shards of {shard} | {r['dask_2']:.2f} | "
          f"{r['dask_2'] / r['cli_2']:.3f} | {r['dask_2_overall']:.2f} |\n")
    print(f"- one sample: {1e3 * c:.1f} ms of one core (`needle tolerance --threads 1`)")
    print(f"- an empty task's round trip: {1e3 * r['noop_latency_s']:.2f} ms (median of 21); "
          f"{args.noop_tasks} empty tasks mapped at once on 2 workers: "
          f"{1e3 * r['noop_per_task_s']:.2f} ms a task")
    print(f"- in the 2-worker study, the workers' time outside the tasks: "
          f"{1e3 * r['study_overhead_per_task_s']:.1f} ms a task (from the first submission "
          "to the last shard written: the tasks' transfer, the client's writes and the idle "
          "tail included)")
    print(f"- the client's reduction of {r['reduce_samples']} samples: {r['reduce_s']:.2f} s, "
          f"{r['reduce_bytes'] / 2**20:.0f} MiB more peak memory")
    print(f"\n**Projection, 10^6 samples on 64 cores** (one worker process a core): shards of "
          f"{p['shard_size']} samples ({p['tasks']} tasks), {p['compute_s']:.0f} s of compute "
          f"({p['compute_s'] / 3600:.2f} h), the scheduler's {p['scheduling_s']:.0f} s hidden "
          f"behind it, and the client's reduction {p['reduce_s']:.0f} s with about "
          f"{p['reduce_bytes'] / 2**30:.1f} GiB: {p['total_s'] / 3600:.2f} h in all.")
    print(json.dumps(r))


if __name__ == "__main__":
    main()
