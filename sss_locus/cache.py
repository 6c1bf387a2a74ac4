"""A small on-disk cache of expensive tabular results (Parquet), safe against partial writes.

Use it in a notebook around the expensive step::

    from sss_locus.cache import cached_frame

    samples = cached_frame(
        {"notebook": "notebooks/pose_space.ipynb", "step": "monte-carlo",
         "parameters": {"n_samples": n_samples, "platform": platform}, "seed": seed},
        lambda: run_monte_carlo(n_samples, platform, seed),
    )

Key
---
The entry key is the SHA-256 of ``key_parts`` (canonical JSON; numpy scalars allowed) together
with the package version and a fingerprint of the package source and ``data/``
(:func:`sss_locus.provenance.code_sha256`): change a parameter, the seed, the code or an input
file and the result is recomputed; change nothing and it is read back in milliseconds. Put in
``key_parts`` everything the result depends on (notebook, step, parameters, seed).

Storage
-------
``<cache>/<key[:2]>/<key>/data.parquet`` plus ``manifest.json`` (key parts, SHA-256 and shape
of the Parquet file, creation time). Each file is written to a temporary name and renamed; the
manifest is written last. An entry whose manifest is missing, unreadable or does not match the
Parquet bytes (partial write, corruption) is deleted and recomputed, never used.

The returned frame is always the one read back from Parquet, so a cache hit and a fresh
computation give identical dtypes.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import uuid
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import pandas as pd

from sss_locus import paths, provenance

CACHE_FORMAT = 1
DATA_NAME = "data.parquet"
MANIFEST_NAME = "manifest.json"


def cache_key(key_parts: Mapping[str, Any]) -> str:
    """SHA-256 hex key of ``key_parts`` plus package version and code fingerprint."""
    if not isinstance(key_parts, Mapping) or not key_parts:
        raise ValueError("key_parts must be a non-empty mapping (notebook, step, parameters, seed, ...)")
    payload = {
        "cache_format": CACHE_FORMAT,
        "key_parts": dict(key_parts),
        "package_version": provenance.package_version(),
        "code_sha256": provenance.code_sha256(),
    }
    text = json.dumps(payload, sort_keys=True, separators=(",", ":"), default=provenance.json_default)
    return hashlib.sha256(text.encode()).hexdigest()


def entry_dir(key: str, cache_dir: Path | None = None) -> Path:
    """Folder of one cache entry."""
    root = paths.cache_dir() if cache_dir is None else Path(cache_dir)
    return root / "frames" / key[:2] / key


def _read_valid(folder: Path, key: str) -> pd.DataFrame | None:
    """The cached frame, or ``None`` when the entry is absent, partial or corrupted."""
    manifest_path = folder / MANIFEST_NAME
    data_path = folder / DATA_NAME
    try:
        manifest = json.loads(manifest_path.read_text(encoding="utf-8"))
        blob = data_path.read_bytes()
    except (OSError, ValueError):
        return None
    if manifest.get("key") != key or manifest.get("sha256") != hashlib.sha256(blob).hexdigest():
        return None
    try:
        frame = pd.read_parquet(data_path)
    except Exception:  # any Parquet decoding failure means the entry is unusable
        return None
    if list(frame.shape) != manifest.get("shape"):
        return None
    return frame


def _write_atomic_bytes(path: Path, blob: bytes) -> None:
    tmp = path.with_name(f".{path.name}.{uuid.uuid4().hex}.tmp")
    tmp.write_bytes(blob)
    os.replace(tmp, path)


def cached_frame(
    key_parts: Mapping[str, Any],
    compute: Callable[[], pd.DataFrame],
    *,
    cache_dir: Path | None = None,
) -> pd.DataFrame:
    """Return ``compute()``, from the cache when a valid entry for ``key_parts`` exists.

    Parameters
    ----------
    key_parts : mapping
        Everything the result depends on (JSON-like values): notebook, step, parameters, seed.
    compute : callable
        Zero-argument function returning a :class:`pandas.DataFrame` (column names strings).
    cache_dir : pathlib.Path, optional
        Cache root; defaults to :func:`sss_locus.paths.cache_dir`.

    Returns
    -------
    pandas.DataFrame
        The frame as stored in (and read back from) Parquet.
    """
    key = cache_key(key_parts)
    folder = entry_dir(key, cache_dir)
    cached = _read_valid(folder, key)
    if cached is not None:
        return cached
    if folder.exists():
        shutil.rmtree(folder, ignore_errors=True)  # partial or corrupted: recompute

    frame = compute()
    if not isinstance(frame, pd.DataFrame):
        raise ValueError(f"compute must return a pandas DataFrame, got {type(frame).__name__}")
    folder.mkdir(parents=True, exist_ok=True)
    tmp_data = folder / f".{DATA_NAME}.{uuid.uuid4().hex}.tmp"
    frame.to_parquet(tmp_data, index=not isinstance(frame.index, pd.RangeIndex))
    blob = tmp_data.read_bytes()
    os.replace(tmp_data, folder / DATA_NAME)
    stored = pd.read_parquet(folder / DATA_NAME)
    manifest = {
        "key": key,
        "key_parts": json.loads(json.dumps(dict(key_parts), default=provenance.json_default)),
        "package_version": provenance.package_version(),
        "sha256": hashlib.sha256(blob).hexdigest(),
        "shape": list(stored.shape),
        "created_utc": provenance.utc_now(),
    }
    _write_atomic_bytes(folder / MANIFEST_NAME, (json.dumps(manifest, indent=2, sort_keys=True) + "\n").encode())
    return stored
