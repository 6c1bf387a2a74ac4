"""On-disk result cache (sss_locus.cache): hits, key sensitivity, corruption recovery."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from sss_locus import cache, provenance
from sss_locus.cache import cache_key, cached_frame, entry_dir

KEY = {"notebook": "notebooks/demo.ipynb", "step": "mc", "parameters": {"n": 5, "platform": "auv"}, "seed": 1}


class Counter:
    """A compute function that counts its calls and returns a seed-dependent frame."""

    def __init__(self, seed: int = 1):
        self.calls = 0
        self.seed = seed

    def __call__(self) -> pd.DataFrame:
        self.calls += 1
        rng = np.random.default_rng(self.seed)
        return pd.DataFrame({"length_m": rng.random(6), "status": np.arange(6, dtype=np.int8),
                             "platform": ["auv"] * 6})


def test_second_call_is_served_from_disk(tmp_path):
    compute = Counter()
    first = cached_frame(KEY, compute, cache_dir=tmp_path)
    second = cached_frame(KEY, compute, cache_dir=tmp_path)
    assert compute.calls == 1
    pd.testing.assert_frame_equal(first, second)
    pd.testing.assert_frame_equal(first, Counter()())  # the stored values are the computed ones


def test_key_ignores_dict_order_and_numpy_scalar_types():
    reordered = {"seed": np.int64(1), "parameters": {"platform": "auv", "n": np.int32(5)},
                 "step": "mc", "notebook": "notebooks/demo.ipynb"}
    assert cache_key(reordered) == cache_key(KEY)


@pytest.mark.parametrize("change", [
    {"seed": 2},
    {"notebook": "notebooks/other.ipynb"},
    {"parameters": {"n": 6, "platform": "auv"}},
    {"parameters": {"n": 5, "platform": "boat"}},
    {"parameters": {"n": 5.0, "platform": "auv"}},
])
def test_any_changed_key_part_recomputes(tmp_path, change):
    compute = Counter()
    cached_frame(KEY, compute, cache_dir=tmp_path)
    cached_frame({**KEY, **change}, compute, cache_dir=tmp_path)
    assert compute.calls == 2


def test_package_version_and_code_are_part_of_the_key(monkeypatch):
    base = cache_key(KEY)
    monkeypatch.setattr(provenance, "package_version", lambda: "999.0")
    assert cache_key(KEY) != base
    monkeypatch.undo()
    monkeypatch.setattr(provenance, "code_sha256", lambda: "0" * 64)
    assert cache_key(KEY) != base


def _corrupt_data(folder):
    data = folder / cache.DATA_NAME
    blob = data.read_bytes()
    data.write_bytes(blob[: len(blob) // 2])


def _flip_one_byte(folder):
    data = folder / cache.DATA_NAME
    blob = bytearray(data.read_bytes())
    blob[len(blob) // 2] ^= 0xFF
    data.write_bytes(bytes(blob))


def _drop_manifest(folder):
    (folder / cache.MANIFEST_NAME).unlink()


def _garble_manifest(folder):
    (folder / cache.MANIFEST_NAME).write_text("{not json")


def _drop_data(folder):
    (folder / cache.DATA_NAME).unlink()


def _wrong_key_in_manifest(folder):
    path = folder / cache.MANIFEST_NAME
    manifest = json.loads(path.read_text())
    manifest["key"] = "0" * 64
    path.write_text(json.dumps(manifest))


@pytest.mark.parametrize("damage", [_corrupt_data, _flip_one_byte, _drop_manifest, _garble_manifest,
                                    _drop_data, _wrong_key_in_manifest])
def test_damaged_entry_is_detected_and_recomputed(tmp_path, damage):
    compute = Counter()
    expected = cached_frame(KEY, compute, cache_dir=tmp_path)
    damage(entry_dir(cache_key(KEY), tmp_path))
    again = cached_frame(KEY, compute, cache_dir=tmp_path)
    assert compute.calls == 2
    pd.testing.assert_frame_equal(again, expected)
    cached_frame(KEY, compute, cache_dir=tmp_path)  # the repaired entry is used again
    assert compute.calls == 2


def test_partial_write_leaves_no_usable_entry(tmp_path):
    """A crash between the data and the manifest (simulated) must not yield a cache hit."""
    def crashing():
        raise KeyboardInterrupt

    compute = Counter()
    folder = entry_dir(cache_key(KEY), tmp_path)
    folder.mkdir(parents=True)
    compute().to_parquet(folder / cache.DATA_NAME)  # data present, manifest never written
    with pytest.raises(KeyboardInterrupt):
        cached_frame(KEY, crashing, cache_dir=tmp_path)
    cached_frame(KEY, compute, cache_dir=tmp_path)
    assert compute.calls == 2  # one above to write the orphan, one real recomputation


def test_non_frame_result_and_bad_key_are_rejected(tmp_path):
    with pytest.raises(ValueError, match="must return a pandas DataFrame"):
        cached_frame(KEY, lambda: [1, 2, 3], cache_dir=tmp_path)
    with pytest.raises(ValueError, match="non-empty mapping"):
        cached_frame({}, Counter(), cache_dir=tmp_path)
    with pytest.raises(ValueError, match="not JSON-like"):
        cached_frame({"f": object()}, Counter(), cache_dir=tmp_path)


def test_default_location_follows_the_environment(tmp_path, monkeypatch):
    monkeypatch.setenv("SSS_LOCUS_CACHE_DIR", str(tmp_path / "c"))
    cached_frame(KEY, Counter())
    assert (tmp_path / "c").is_dir() and any((tmp_path / "c").rglob(cache.MANIFEST_NAME))
