"""An on-disk cache of expensive tabular results (Parquet), safe against partial writes.

Wrap the expensive function where it is called (the experiments layer never imports the cache)::

    from sss_locus.experiments.survey_passes.study import simulate_passes
    from sss_locus.pipeline.run.cache import cached

    samples, acceptance = cached(simulate_passes)(platform, envelope, model, angles, n, seed)

Key
---
The entry key is the SHA-256 of the function's qualified name, its bound arguments (defaults
applied; dataclasses by their compared fields, numpy values as numbers, so equal inputs give one
key however they were spelled), the package version and a fingerprint of what a result can
depend on: ``sss_locus/geometry/``, ``sss_locus/experiments/`` and ``data/``
(:func:`sss_locus.pipeline.publish.provenance.science_sha256`). Editing a plot, the book builder or a
notebook never invalidates a simulation; editing a kernel, a sampler or an input file always does.
The seed is an argument like any other.

Storage
-------
``<cache>/frames/<key[:2]>/<key>/data-<i>.parquet`` (one file per returned frame) plus
``manifest.json`` (key parts, SHA-256 and shape of each Parquet file, the data entries the
computation read, creation time). A new entry
is written complete into a private temporary folder (``.tmp-<key>-<pid>-<random>``) and renamed to
its final name in one step, so an entry folder another process can see is always complete; if two
processes compute one entry at once, the first rename wins and the other uses its own result.
Anything else found under an entry's name (a manifest that is not an object, missing or altered
Parquet files, a file instead of a folder, an entry of an older format) is renamed aside, deleted
and recomputed, never used; nothing is deleted that another process may still be writing.

``sss-locus cache`` shows the size; ``sss-locus cache --prune`` (:func:`prune`) deletes entries
no current input reaches (made by other code, data or package version: their keys can never be
asked for again), broken entries, and temporary folders whose writer is gone.

The returned frames are always the ones read back from Parquet, so a cache hit and a fresh
computation give identical dtypes. A hit also records, for the run, the data entries its
computation read (:func:`sss_locus.experiments.datamodel.datadoc.note_read`): a figure computed from a
cached result names the same data files (and goes stale on the same edits) as one computed afresh.
"""

from __future__ import annotations

import dataclasses
import functools
import hashlib
import inspect
import json
import os
import shutil
import time
import uuid
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from sss_locus import paths
from sss_locus.experiments.datamodel import datadoc
from sss_locus.pipeline.run import atomic, orphans, progress
from sss_locus.pipeline.publish import provenance

CACHE_FORMAT = 3  # 3: entries record the data entries their computation read
DATA_NAME = "data-{index}.parquet"
MANIFEST_NAME = "manifest.json"


def cache_key(key_parts: Mapping[str, Any]) -> str:
    """SHA-256 hex key of ``key_parts`` plus package version and science fingerprint."""
    if not isinstance(key_parts, Mapping) or not key_parts:
        raise ValueError("key_parts must be a non-empty mapping (function, arguments, ...)")
    payload = {
        "cache_format": CACHE_FORMAT,
        "key_parts": dict(key_parts),
        "package_version": provenance.package_version(),
        "science_sha256": provenance.science_sha256(),
    }
    text = json.dumps(payload, sort_keys=True, separators=(",", ":"), default=provenance.json_default)
    return hashlib.sha256(text.encode()).hexdigest()


def entry_dir(key: str, cache_dir: Path | None = None) -> Path:
    """Folder of one cache entry."""
    root = paths.cache_dir() if cache_dir is None else Path(cache_dir)
    return root / "frames" / key[:2] / key


def _read_valid(folder: Path, key: str) -> tuple[bool, list[pd.DataFrame] | None, list[str]]:
    """``(is_tuple, frames, data_reads)`` of a valid entry; ``frames`` is None when it is absent,
    partial or corrupted."""
    try:
        manifest = json.loads((folder / MANIFEST_NAME).read_text(encoding="utf-8"))
        files, reads = manifest["files"], manifest["data_reads"]
        if not isinstance(manifest, dict) or not isinstance(files, list) or not isinstance(reads, list):
            return False, None, []
        frames = []
        for index, entry in enumerate(files):
            path = folder / DATA_NAME.format(index=index)
            if hashlib.sha256(path.read_bytes()).hexdigest() != entry["sha256"]:
                return False, None, []
            frame = pd.read_parquet(path)
            if list(frame.shape) != entry["shape"]:
                return False, None, []
            frames.append(frame)
        if manifest.get("key") != key or not frames:
            return False, None, []
        return bool(manifest.get("is_tuple")), frames, [str(r) for r in reads]
    except Exception:  # unreadable, not JSON, wrong shape, bad Parquet: the entry is unusable
        return False, None, []


def _noting_reads(compute: Callable[[], Any]) -> tuple[Any, list[str]]:
    """``compute()`` and the data entries its loaders read (:func:`sss_locus.experiments.datamodel.datadoc.recording`),
    which the run's own recording, if any, gets too."""
    with datadoc.recording() as reads:
        result = compute()
    return result, sorted(reads)


def cached_result(
    key_parts: Mapping[str, Any],
    compute: Callable[[], pd.DataFrame | tuple[pd.DataFrame, ...]],
    *,
    cache_dir: Path | None = None,
) -> pd.DataFrame | tuple[pd.DataFrame, ...]:
    """Return ``compute()``, from the cache when a valid entry for ``key_parts`` exists.

    Parameters
    ----------
    key_parts : mapping
        Everything the result depends on (JSON-like values).
    compute : callable
        Zero-argument function returning a :class:`pandas.DataFrame` or a tuple of them
        (column names strings).
    cache_dir : pathlib.Path, optional
        Cache root; defaults to :func:`sss_locus.paths.cache_dir`.

    Returns
    -------
    pandas.DataFrame or tuple of pandas.DataFrame
        As ``compute`` returns it, each frame as stored in (and read back from) Parquet.
    """
    key = cache_key(key_parts)
    folder = entry_dir(key, cache_dir)
    is_tuple, frames, reads = _read_valid(folder, key)
    if frames is not None:
        datadoc.note_read(*reads)  # a hit read what its computation read: the run's record says so
        return tuple(frames) if is_tuple else frames[0]
    if folder.exists() or folder.is_symlink():
        _discard(folder)  # broken (complete entries appear in one rename): recompute

    result, reads = _noting_reads(compute)
    is_tuple = isinstance(result, tuple)
    frames = list(result) if is_tuple else [result]
    if not frames or not all(isinstance(f, pd.DataFrame) for f in frames):
        raise ValueError("compute must return a pandas DataFrame or a tuple of DataFrames, got "
                         f"{type(result).__name__}")
    parent = folder.parent
    if parent.exists() and not parent.is_dir():
        _discard(parent)
    parent.mkdir(parents=True, exist_ok=True)
    tmp = parent / f".tmp-{key}-{os.getpid()}-{uuid.uuid4().hex[:12]}"
    try:
        tmp.mkdir()
        stored, files = [], []
        for index, frame in enumerate(frames):
            target = tmp / DATA_NAME.format(index=index)
            frame.to_parquet(target, index=not isinstance(frame.index, pd.RangeIndex),
                             use_dictionary=_categorical_columns(frame))
            back = pd.read_parquet(target)
            stored.append(back)
            files.append({"sha256": hashlib.sha256(target.read_bytes()).hexdigest(), "shape": list(back.shape)})
        manifest = {
            "key": key,
            "key_parts": json.loads(json.dumps(dict(key_parts), default=provenance.json_default)),
            "package_version": provenance.package_version(),
            "is_tuple": is_tuple,
            "files": files,
            "data_reads": reads,
            "created_utc": provenance.utc_now(),
        }
        (tmp / MANIFEST_NAME).write_text(json.dumps(manifest, indent=2, sort_keys=True) + "\n", encoding="utf-8")
        try:
            os.rename(tmp, folder)  # atomic; fails if another process got there first
        except OSError:
            pass  # theirs is as good as ours
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return tuple(stored) if is_tuple else stored[0]


def _categorical_columns(frame: pd.DataFrame) -> list[str]:
    """The columns written with Parquet's dictionary encoding: the categorical ones (their
    categories are stored with them). pyarrow would try it on every column and give it up on
    continuous numbers, which roughly doubles the time to write a Monte Carlo table; the values
    read back are the same either way."""
    return [str(c) for c, dtype in frame.dtypes.items() if isinstance(dtype, pd.CategoricalDtype)]


def _discard(path: Path) -> None:
    """Rename ``path`` aside (one step, so no reader sees it half-deleted), then delete it."""
    aside = atomic.temp_name(path, "trash")
    try:
        os.rename(path, aside)
    except OSError:
        return  # already gone (another process discarded it)
    if aside.is_dir() and not aside.is_symlink():
        shutil.rmtree(aside, ignore_errors=True)
    else:
        aside.unlink(missing_ok=True)


def _entries(root: Path) -> list[Path]:
    frames = root / "frames"
    if not frames.is_dir():
        return []
    return [p for shard in frames.iterdir() if shard.is_dir() for p in shard.iterdir()]


def _size(path: Path) -> int:
    if path.is_file() or path.is_symlink():
        return path.lstat().st_size
    return sum(p.lstat().st_size for p in path.rglob("*") if p.is_file())


def usage(cache_dir: Path | None = None, *, prune_unreachable: bool = False) -> dict[str, int]:
    """Entries, bytes and entries reachable by the current inputs; with ``prune_unreachable``,
    also delete the rest (see :func:`prune`)."""
    root = paths.cache_dir() if cache_dir is None else Path(cache_dir)
    report = {"entries": 0, "bytes": 0, "reachable": 0, "removed": 0, "freed": 0}
    for path in _entries(root):
        size = _size(path)
        if path.name.startswith("."):  # a temporary folder or trash
            if prune_unreachable and not atomic.pid_alive(atomic.pid_of_temp(path)) \
                    and time.time() - path.lstat().st_mtime > 60:
                _discard(path)
                report["removed"] += 1
                report["freed"] += size
            continue
        report["entries"] += 1
        report["bytes"] += size
        reachable = False
        try:
            manifest = json.loads((path / MANIFEST_NAME).read_text(encoding="utf-8"))
            reachable = (isinstance(manifest, dict) and manifest.get("key") == path.name
                         and cache_key(manifest["key_parts"]) == path.name
                         and _read_valid(path, path.name)[1] is not None)
        except Exception:  # unreadable or malformed: not reachable
            reachable = False
        report["reachable"] += reachable
        if prune_unreachable and not reachable:
            _discard(path)
            report["removed"] += 1
            report["freed"] += size
    return report


def prune(cache_dir: Path | None = None) -> dict[str, int]:
    """Delete entries no current input reaches: their key, recomputed from the key parts they
    record with today's package version and code/data fingerprint, is not their name (or they
    are broken); and temporary folders whose writing process is gone. Returns the counts of
    :func:`usage` (taken before deleting) plus ``removed`` and ``freed`` bytes. With the default
    cache it also deletes the build area's staging folders of runs that were killed
    (:func:`sss_locus.pipeline.run.orphans.remove_stale_staging`) and the hidden files of commits
    killed midway beside its figures and executed copies
    (:func:`sss_locus.pipeline.run.orphans.remove_stale_temporaries`)."""
    report = usage(cache_dir, prune_unreachable=True)
    if cache_dir is None:
        for removed, freed in (orphans.remove_stale_staging(paths.build_dir() / "tmp"),
                               orphans.remove_stale_temporaries(paths.figures_dir(), paths.executed_dir())):
            report["removed"] += removed
            report["freed"] += freed
    return report


def canonical(value: Any, name: str = "argument") -> Any:
    """A JSON-like form of ``value`` for a cache key: dataclasses by their compared fields (with
    the type name), mappings with string keys, sequences and numpy arrays as lists, numpy scalars
    as numbers, DataFrames by a hash of their content (values, index, column names, dtypes).
    Anything else raises ``TypeError`` naming ``name``."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        fields = {f.name: canonical(getattr(value, f.name), f"{name}.{f.name}")
                  for f in dataclasses.fields(value) if f.compare}
        return {"__type__": type(value).__qualname__, **fields}
    if isinstance(value, Mapping):
        return {str(k): canonical(v, f"{name}[{k!r}]") for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [canonical(v, f"{name}[{i}]") for i, v in enumerate(value)]
    if isinstance(value, np.ndarray):
        return canonical(value.tolist(), name)
    if isinstance(value, pd.DataFrame):  # by content: values, index, column names and dtypes
        digest = hashlib.sha256(pd.util.hash_pandas_object(value, index=True).to_numpy().tobytes())
        digest.update(json.dumps([[str(c), str(t)] for c, t in value.dtypes.items()]).encode())
        return {"__type__": "DataFrame", "shape": list(value.shape), "sha256": digest.hexdigest()}
    if isinstance(value, np.generic):
        return value.item()
    if value is None or isinstance(value, (bool, int, float, str)):
        return value
    raise TypeError(f"cached: {name} of type {type(value).__name__} cannot be part of a cache key "
                    "(use numbers, strings, lists, dicts, numpy arrays, DataFrames or dataclasses of them)")


def cached(fn: Callable[..., Any], *, cache_dir: Path | None = None) -> Callable[..., Any]:
    """``fn`` with its results cached on disk (see the module docstring for the key).

    ``fn`` must return a DataFrame or a tuple of DataFrames. The wrapper has ``fn``'s signature;
    its call binds the arguments (defaults applied) and looks them up before computing. An
    argument ``progress`` (a callback that observes a study's batches) is not part of the key;
    left ``None``, it becomes :func:`sss_locus.pipeline.run.progress.batch_reporter`.
    """
    signature = inspect.signature(fn)
    qualname = f"{fn.__module__}.{fn.__qualname__}"

    @functools.wraps(fn)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        bound = signature.bind(*args, **kwargs)
        bound.apply_defaults()
        if bound.arguments.get("progress", False) is None:  # a study's batches, shown by the runner
            bound.arguments["progress"] = progress.batch_reporter(fn.__name__)
        arguments = {k: canonical(v, k) for k, v in bound.arguments.items() if k != "progress"}
        return cached_result({"function": qualname, "arguments": arguments},
                             lambda: fn(*bound.args, **bound.kwargs), cache_dir=cache_dir)

    return wrapper
