"""needle.shards: a distributed study's pure tasks and the files they leave (needle.distributed).

The case as a task ships it (its text and the files it names, with their hash), the task itself
(run_shard: a range of samples computed by needle.tolerance_shard on whichever machine), and
the shard files: written atomically as NumPy .npz with the study's metadata, read back, and the
ranges of a study that no shard written so far covers.
"""

import hashlib
import json
import os
import socket
import tempfile
import time
import tomllib

import numpy as np

import needle

SHARD_PREFIX = "tolerance-"


class BadInput(Exception):
    """A one-line message about the user's input: exit status 2."""


class TaskFailed(Exception):
    """A task the cluster gave up on: one line, exit status 3."""


# The case, as shipped: its text and the files it names.


def case_bundle(path):
    """The case file `path` as a task ships it: {'path', 'text', 'files': {name: bytes},
    'sha256'}; raises BadInput when needle refuses the case."""
    try:
        with open(path, "rb") as f:
            raw = f.read()
    except OSError as e:
        raise BadInput(f"{path}: cannot read the case file ({e.strerror})") from None
    try:
        text = raw.decode("utf-8")
        sections = tomllib.loads(text)
    except (UnicodeDecodeError, tomllib.TOMLDecodeError):
        sections = None  # needle's own loader names the problem below
    try:
        needle.load_case(path)
    except needle.CaseError as e:
        raise BadInput(str(e)) from None
    files = {}
    csv = (sections or {}).get("lift", {}).get("csv")
    if isinstance(csv, str):
        if os.path.isabs(csv) or ".." in csv.replace("\\", "/").split("/"):
            raise BadInput(f"{path}: [lift] csv: {csv!r}: a distributed study ships the table; "
                           "expected a path inside the case's folder")
        with open(os.path.join(os.path.dirname(path), csv), "rb") as f:
            files[csv] = f.read()
    digest = hashlib.sha256(raw)
    for name in sorted(files):
        digest.update(b"\0" + name.encode() + b"\0" + files[name])
    return {"path": path, "text": text, "files": files, "sha256": digest.hexdigest()}


def _materialized(bundle):
    """The path a worker reads the case as: the case's own when it names no file, else one in a
    folder of this machine's temporary files holding the files it names (the text itself is
    parsed as shipped)."""
    if not bundle["files"]:
        return bundle["path"]
    digest = hashlib.sha256()
    for name in sorted(bundle["files"]):
        digest.update(name.encode() + b"\0" + bundle["files"][name] + b"\0")
    folder = os.path.join(tempfile.gettempdir(), "needle-case-" + digest.hexdigest()[:16])
    for name, content in bundle["files"].items():
        target = os.path.join(folder, name)
        if os.path.exists(target):
            continue
        os.makedirs(os.path.dirname(target), exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=os.path.dirname(target))
        with os.fdopen(fd, "wb") as f:
            f.write(content)
        os.replace(tmp, target)
    return os.path.join(folder, os.path.basename(bundle["path"]) or "case.toml")


def run_shard(bundle, seed, first, count, threads=1):
    """One task: samples [first, first + count) of the seed's study of the shipped case, as
    needle.tolerance_shard's arrays (plus 'seconds' of compute and the 'worker')."""
    start = time.perf_counter()
    shard = needle.tolerance_shard(bundle["text"], path=_materialized(bundle),
                                   shown_as=bundle["path"], seed=seed, first_sample=first,
                                   samples=count, threads=threads)
    shard["seconds"] = time.perf_counter() - start
    shard["worker"] = f"{socket.gethostname()}:{os.getpid()}"
    return shard


# Shard files.


def shard_name(first, count):
    return f"{SHARD_PREFIX}{first:010d}-{count:07d}.npz"


def write_shard(folder, meta, shard):
    """Writes a shard atomically (a reader sees the whole file or none)."""
    arrays = {
        "meta": np.array(json.dumps(dict(meta, case_digest=shard.get("case_digest")),
                                    sort_keys=True)),
        "input_keys": np.array(shard["input_keys"], dtype=str),
        "inputs": shard["inputs"],
        "input_present": shard["input_present"],
        "output_keys": np.array(shard["output_keys"], dtype=str),
        "outputs": shard["outputs"],
        "output_present": shard["output_present"],
        "pass": shard["pass"],
        "failing": np.array([json.dumps(f) for f in shard["failing"]], dtype=str),
        "refused": np.array(shard["refused"], dtype=str),
    }
    path = os.path.join(folder, shard_name(meta["first_sample"], meta["samples"]))
    fd, tmp = tempfile.mkstemp(dir=folder, suffix=".part")
    with os.fdopen(fd, "wb") as f:
        np.savez_compressed(f, **arrays)
    _publish(tmp, path)
    return path


def _publish(tmp, path):
    """Renames a finished temporary file to its name, with the permissions of a new file."""
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(tmp, 0o666 & ~umask)
    os.replace(tmp, path)


def read_shard(path):
    """(meta, shard dict as tolerance_reduce takes it), or None for an unreadable file."""
    try:
        with np.load(path, allow_pickle=False) as z:
            meta = json.loads(str(z["meta"]))
            n = int(meta["samples"])
            shard = {
                "seed": int(meta["seed"]),
                "first_sample": int(meta["first_sample"]),
                "samples": n,
                "input_keys": [str(k) for k in z["input_keys"]],
                "inputs": z["inputs"].reshape(n, -1),
                "input_present": z["input_present"].reshape(n, -1),
                "output_keys": [str(k) for k in z["output_keys"]],
                "outputs": z["outputs"].reshape(n, -1),
                "output_present": z["output_present"].reshape(n, -1),
                "pass": z["pass"],
                "failing": [json.loads(str(f)) for f in z["failing"]],
                "refused": [str(r) for r in z["refused"]],
            }
            if meta.get("case_digest"):
                shard["case_digest"] = str(meta["case_digest"])
    except (OSError, ValueError, KeyError, json.JSONDecodeError):
        return None
    return meta, shard


def existing_shards(folder, study):
    """The shards already written for this study inside its range, by first sample. A shard of
    another case or seed in the folder is refused (BadInput): --out names one study's folder."""
    found = {}
    for name in sorted(os.listdir(folder)):
        if not (name.startswith(SHARD_PREFIX) and name.endswith(".npz")):
            continue
        read = read_shard(os.path.join(folder, name))
        if read is None:
            continue  # a damaged file: its samples are computed again
        meta, shard = read
        if meta.get("case_sha256") != study["case_sha256"] or meta.get("seed") != study["seed"]:
            raise BadInput(f"--out: {folder} holds shards of another study ({name}: case "
                           f"{meta.get('case')}, seed {meta.get('seed')}); expected a new folder "
                           "or this study's")
        first, n = shard["first_sample"], shard["samples"]
        if first >= study["first_sample"] and first + n <= study["end"]:
            found[first] = shard
    # Overlapping shards (of studies cut into other sizes): keep a chain that does not overlap.
    chain, end = {}, -1
    for first in sorted(found):
        if first >= end:
            chain[first] = found[first]
            end = first + found[first]["samples"]
    return chain


def missing_ranges(begin, end, have):
    """The ranges of [begin, end) no shard in `have` covers."""
    gaps, at = [], begin
    for first in sorted(have):
        if first > at:
            gaps.append((at, first))
        at = max(at, first + have[first]["samples"])
    if at < end:
        gaps.append((at, end))
    return gaps


def split(gaps, size):
    return [(a, min(size, hi - a)) for lo, hi in gaps for a in range(lo, hi, size)]
