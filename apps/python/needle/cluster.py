"""needle.cluster: the Dask side of a distributed study (needle.distributed).

A client to a scheduler or to a local cluster, the scheduler's time per task and the task size
chosen from it, and the progress line on stderr.
"""

import logging
import math
import os
import sys
import time

from needle.shards import BadInput

#: The most of a shard's time the scheduler may take (the task size is chosen for it).
OVERHEAD_SHARE = 0.01


# The cluster.


def connect(scheduler, workers, timeout):
    """A Dask client: to the scheduler's address, or to a local cluster of `workers` processes
    (0: this machine's cores), one thread each."""
    try:
        from distributed import Client, LocalCluster
    except ImportError as e:
        raise BadInput(f"Dask's distributed is not installed for {sys.executable} ({e}); "
                       "bash scripts/install-deps.sh installs python3-distributed") from None
    if scheduler:
        try:
            client = Client(scheduler, timeout=timeout)
        except (OSError, TimeoutError, ValueError) as e:
            raise BadInput(f"--scheduler {scheduler}: no Dask scheduler answered within "
                           f"{timeout:g} s ({type(e).__name__}: {str(e).splitlines()[0]})"
                           ) from None
        try:
            client.wait_for_workers(1, timeout=timeout)
        except (OSError, TimeoutError):
            # wait_for_workers leaves a future of Dask's own holding the timeout: asyncio logs it
            # on stderr when it is collected ("Future exception was never retrieved", seen on a
            # loaded machine), after the one line this error is. It is this error: not logged.
            logging.getLogger("asyncio").setLevel(logging.CRITICAL)
            client.close()
            raise BadInput(f"--scheduler {scheduler}: the scheduler has no worker after "
                           f"{timeout:g} s (start dask-worker {scheduler} on the workers' "
                           "machines)") from None
        return client, None
    cluster = LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1,
                           processes=True, host="127.0.0.1",
                           dashboard_address=":0")  # any free port
    return Client(cluster, timeout=timeout), cluster


def _scheduler_has_bokeh(client):
    """Whether the scheduler serves Dask's dashboard: it needs Bokeh where the scheduler runs
    (Debian 12 packages none). Asked by a function sent by value (the scheduler's machine need
    not have needle)."""
    try:
        return bool(client.run_on_scheduler(
            lambda: __import__("importlib.util").util.find_spec("bokeh") is not None))
    except Exception:  # an older scheduler that refuses run_on_scheduler: no address printed
        return False


def _noop(i):
    return i


def task_overhead(client, rounds=8):
    """The scheduler's time per task, s: the median round trip of a task that does nothing."""
    times = []
    for i in range(rounds):
        start = time.perf_counter()
        client.submit(_noop, i, pure=False).result()
        times.append(time.perf_counter() - start)
    return sorted(times)[len(times) // 2]


def choose_shard_size(samples, slots, seconds_per_sample, overhead_s):
    """Samples per task: at least enough that the scheduler's time per task stays under 1 % of
    the task's; then about four tasks per worker thread (a lost shard costs a quarter of a
    thread's share), and at most 5 minutes of one core."""
    share = overhead_s / (OVERHEAD_SHARE * max(seconds_per_sample, 1e-9))
    floor = max(1, math.ceil(share * (1.0 - 1e-12)))  # 10.000000000000002 is 10
    ceiling = max(floor, math.floor(300.0 / max(seconds_per_sample, 1e-9)))
    balanced = math.ceil(samples / (4 * max(1, slots)))
    return min(samples, max(floor, min(balanced, ceiling)))


class Progress:
    """Shards done, samples per second and the time left, on stderr (a terminal: one line
    redrawn; else a line at most every 5 s and at the end)."""

    def __init__(self, shards, samples, enabled, names=("tolerance", "shards", "samples")):
        self.shards, self.samples, self.enabled = shards, samples, enabled
        self.names = names
        self.tty = sys.stderr.isatty()
        self.start = time.perf_counter()
        self.shown = 0.0
        self.done_shards = self.done_samples = 0

    def update(self, n):
        self.done_shards += 1
        self.done_samples += n
        now = time.perf_counter()
        if not self.enabled or (not self.tty and now - self.shown < 5.0
                                and self.done_shards < self.shards):
            return
        self.shown = now
        rate = self.done_samples / max(now - self.start, 1e-9)
        left = (self.samples - self.done_samples) / rate if rate > 0 else math.inf
        what, tasks, items = self.names
        line = (f"{what}: {self.done_shards}/{self.shards} {tasks}, {self.done_samples}/"
                f"{self.samples} {items}, {rate:.3g} {items}/s, {left:.0f} s left")
        end = "\n" if not self.tty or self.done_shards == self.shards else ""
        sys.stderr.write(("\r" if self.tty else "") + line + end)
        sys.stderr.flush()
