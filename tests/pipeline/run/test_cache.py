"""On-disk result cache (sss_locus.pipeline.run.cache): hits, key sensitivity, corruption recovery,
the cached(fn) wrapper and what its fingerprint covers."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from sss_locus.pipeline.run import cache
from sss_locus.pipeline.publish import provenance
from sss_locus.pipeline.run.cache import cache_key, cached, cached_result, entry_dir

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
    first = cached_result(KEY, compute, cache_dir=tmp_path)
    second = cached_result(KEY, compute, cache_dir=tmp_path)
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
    cached_result(KEY, compute, cache_dir=tmp_path)
    cached_result({**KEY, **change}, compute, cache_dir=tmp_path)
    assert compute.calls == 2


def test_package_version_and_code_are_part_of_the_key(monkeypatch):
    base = cache_key(KEY)
    monkeypatch.setattr(provenance, "package_version", lambda: "999.0")
    assert cache_key(KEY) != base
    monkeypatch.undo()
    monkeypatch.setattr(provenance, "science_sha256", lambda: "0" * 64)
    assert cache_key(KEY) != base


def _corrupt_data(folder):
    data = folder / cache.DATA_NAME.format(index=0)
    blob = data.read_bytes()
    data.write_bytes(blob[: len(blob) // 2])


def _flip_one_byte(folder):
    data = folder / cache.DATA_NAME.format(index=0)
    blob = bytearray(data.read_bytes())
    blob[len(blob) // 2] ^= 0xFF
    data.write_bytes(bytes(blob))


def _drop_manifest(folder):
    (folder / cache.MANIFEST_NAME).unlink()


def _garble_manifest(folder):
    (folder / cache.MANIFEST_NAME).write_text("{not json")


def _drop_data(folder):
    (folder / cache.DATA_NAME.format(index=0)).unlink()


def _wrong_key_in_manifest(folder):
    path = folder / cache.MANIFEST_NAME
    manifest = json.loads(path.read_text())
    manifest["key"] = "0" * 64
    path.write_text(json.dumps(manifest))


@pytest.mark.parametrize("damage", [_corrupt_data, _flip_one_byte, _drop_manifest, _garble_manifest,
                                    _drop_data, _wrong_key_in_manifest])
def test_damaged_entry_is_detected_and_recomputed(tmp_path, damage):
    compute = Counter()
    expected = cached_result(KEY, compute, cache_dir=tmp_path)
    damage(entry_dir(cache_key(KEY), tmp_path))
    again = cached_result(KEY, compute, cache_dir=tmp_path)
    assert compute.calls == 2
    pd.testing.assert_frame_equal(again, expected)
    cached_result(KEY, compute, cache_dir=tmp_path)  # the repaired entry is used again
    assert compute.calls == 2


def test_partial_write_leaves_no_usable_entry(tmp_path):
    """A crash between the data and the manifest (simulated) must not yield a cache hit."""
    def crashing():
        raise KeyboardInterrupt

    compute = Counter()
    folder = entry_dir(cache_key(KEY), tmp_path)
    folder.mkdir(parents=True)
    compute().to_parquet(folder / cache.DATA_NAME.format(index=0))  # data present, manifest never written
    with pytest.raises(KeyboardInterrupt):
        cached_result(KEY, crashing, cache_dir=tmp_path)
    cached_result(KEY, compute, cache_dir=tmp_path)
    assert compute.calls == 2  # one above to write the orphan, one real recomputation


def test_non_frame_result_and_bad_key_are_rejected(tmp_path):
    with pytest.raises(ValueError, match="must return a pandas DataFrame or a tuple"):
        cached_result(KEY, lambda: [1, 2, 3], cache_dir=tmp_path)
    with pytest.raises(ValueError, match="non-empty mapping"):
        cached_result({}, Counter(), cache_dir=tmp_path)
    with pytest.raises(ValueError, match="not JSON-like"):
        cached_result({"f": object()}, Counter(), cache_dir=tmp_path)


def test_default_location_follows_the_environment(tmp_path, monkeypatch):
    monkeypatch.setenv("SSS_LOCUS_CACHE_DIR", str(tmp_path / "c"))
    cached_result(KEY, Counter())
    assert (tmp_path / "c").is_dir() and any((tmp_path / "c").rglob(cache.MANIFEST_NAME))


# --- cached(fn): the wrapper the notebooks use -------------------------------------------------
from dataclasses import dataclass, field  # noqa: E402


@dataclass(frozen=True)
class Spec:
    n: int
    scale: float = 1.0
    note: str = field(default="", compare=False)  # not compared: not part of the key


class Simulation:
    """A function-like object counting calls; returns a frame or a tuple of frames."""

    def __init__(self, pair: bool = False):
        self.calls, self.pair = 0, pair
        self.__module__, self.__qualname__ = __name__, f"Simulation{int(pair)}"

    def __call__(self, spec: Spec, angles, seed: int = 0):
        self.calls += 1
        rng = np.random.default_rng(seed)
        a = pd.DataFrame({"angle": np.asarray(angles, float).repeat(spec.n),
                          "value": spec.scale * rng.random(len(angles) * spec.n)})
        return (a, a.describe()) if self.pair else a


def test_cached_wrapper_keys_on_arguments_not_their_spelling(tmp_path):
    sim = Simulation()
    run = cached(sim, cache_dir=tmp_path)
    first = run(Spec(3), [0.0, 10.0], seed=1)
    again = run(Spec(3, note="other note"), np.array([0.0, 10.0]), np.int64(1))  # same values
    assert sim.calls == 1
    pd.testing.assert_frame_equal(first, again)
    pd.testing.assert_frame_equal(first, Simulation()(Spec(3), [0, 10], 1))
    for changed in ((Spec(4), [0.0, 10.0], 1), (Spec(3, 2.0), [0.0, 10.0], 1), (Spec(3), [0.0, 20.0], 1),
                    (Spec(3), [0.0, 10.0], 2)):
        run(*changed)
    assert sim.calls == 5


def test_cached_wrapper_returns_tuples_as_computed(tmp_path):
    sim = Simulation(pair=True)
    run = cached(sim, cache_dir=tmp_path)
    fresh = run(Spec(2), [5], 0)
    hit = run(Spec(2), [5], 0)
    assert sim.calls == 1 and isinstance(hit, tuple) and len(hit) == 2
    for a, b in zip(fresh, hit):
        pd.testing.assert_frame_equal(a, b)


def test_cached_wrapper_refuses_unkeyable_arguments(tmp_path):
    with pytest.raises(TypeError, match="angles.*cannot be part of a cache key"):
        cached(Simulation(), cache_dir=tmp_path)(Spec(2), object())


def test_science_fingerprint_covers_geometry_experiments_and_data_only(tmp_path, monkeypatch):
    """Editing report/ or pipeline/ keeps cached simulations; editing a kernel or data does not."""
    from sss_locus import paths

    root = tmp_path / "repo"
    for rel in ("sss_locus/geometry/k.py", "sss_locus/experiments/e.py", "sss_locus/report/r.py",
                "sss_locus/pipeline/p.py", "data/x.toml"):
        (root / rel).parent.mkdir(parents=True, exist_ok=True)
        (root / rel).write_text("a = 1\n")
    monkeypatch.setattr(paths, "REPO_ROOT", root)
    monkeypatch.setattr(paths, "PACKAGE_DIR", root / "sss_locus")
    monkeypatch.setattr(paths, "DATA_DIR", root / "data")
    base = provenance.science_sha256()
    for rel in ("sss_locus/report/r.py", "sss_locus/pipeline/p.py"):
        (root / rel).write_text("a = 2\n")
        assert provenance.science_sha256() == base, rel
    for rel in ("sss_locus/geometry/k.py", "sss_locus/experiments/e.py", "data/x.toml"):
        (root / rel).write_text("a = 3\n")
        assert provenance.science_sha256() != base, rel
        base = provenance.science_sha256()


def test_a_hit_records_the_data_entries_its_computation_read(tmp_path, monkeypatch):
    """A run records the data entries its loaders read (the figure's data files and what makes it
    stale). A cached result read them only when it was computed: the entry keeps them and a hit
    records them again, so the run of a warm cache names what the run of a cold one does."""
    from sss_locus.experiments.datamodel import datadoc
    from sss_locus.experiments.datamodel.platforms import load_platform

    def compute():
        load_platform("auv")  # a loader: notes platforms.auv and its sonar
        return pd.DataFrame({"x": [1.0]})

    def run():
        with datadoc.recording() as reads:  # a run's recording (the kernel's, context.enter_kernel)
            cached_result(KEY, compute, cache_dir=tmp_path / "cache")
        return reads

    cold, warm = run(), run()
    assert "platforms.auv" in cold and any(e.startswith("sonars.") for e in cold)
    assert warm == cold  # a hit notes what its computation read
    cached_result({**KEY, "seed": 9}, compute, cache_dir=tmp_path / "cache")  # outside a run: nothing noted
    assert datadoc.reads_so_far() is None


def test_an_entry_without_its_data_reads_is_recomputed(tmp_path):
    compute = Counter()
    cached_result(KEY, compute, cache_dir=tmp_path)
    manifest_path = entry_dir(cache_key(KEY), tmp_path) / cache.MANIFEST_NAME
    manifest = json.loads(manifest_path.read_text())
    del manifest["data_reads"]  # as an entry written before entries recorded them
    manifest_path.write_text(json.dumps(manifest))
    cached_result(KEY, compute, cache_dir=tmp_path)
    assert compute.calls == 2
