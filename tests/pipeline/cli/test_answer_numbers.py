"""``sss-locus answer`` prints the numbers it used (issue 38, items 5 and 6): the replicate
batches its intervals came from (``-p n_batches 10000 -p n_samples 100`` used 33, printed
10,000), and a too-small ``n_per_angle`` is refused naming the parameter before any work."""

from __future__ import annotations

import re

import pytest

from sss_locus.experiments.stats.replicates import batch_count
from sss_locus.pipeline.cli import command as cli
from sss_locus.pipeline.cli.answer import answer


@pytest.fixture
def private_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("SSS_LOCUS_CACHE_DIR", str(tmp_path / "cache"))


def test_the_printed_batches_are_the_batches_used(private_cache):
    lines = []
    result = answer("auv", "quick", [["n_batches", "10000"], ["n_samples", "100"]], log=lines.append)
    used = result["rho"].attrs["n_batches"]
    assert used == batch_count(result["n_pose"] // 3, 10000) < 10000  # the replicates module's own rule
    text = next(line for line in lines if "replicate batches" in line)
    assert re.search(rf"\b{used} replicate batches", text) and "10000 asked" in text.replace(",", "")


def test_n_per_angle_below_three_names_the_parameter(capsys):
    assert cli.main(["answer", "-p", "platform", "auv", "-p", "n_per_angle", "[1]"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "n_per_angle" in err and "[3, 1000000]" in err, err
