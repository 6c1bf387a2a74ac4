"""A user's XTF file read only in part (cut short inside its last packet): the run's warnings
name it, from the observations parameter as the runner resolves it (absolute or relative to the
repository); whole files, sightings CSVs and runs without observations give none."""

from __future__ import annotations

import shutil

from sss_locus.paths import DATA_DIR, REPO_ROOT
from sss_locus.pipeline.run import userfiles

REAL = DATA_DIR / "examples" / "your_pings" / "real"


def test_a_cut_xtf_file_of_the_observations_is_a_run_warning(tmp_path):
    shutil.copy(REAL / "scotsman_matches.csv", tmp_path / "m.csv")
    data = (REAL / "scotsman-iver2.xtf").read_bytes()
    packet = int.from_bytes(data[1024 + 10:1024 + 14], "little")  # every packet of the file has this length
    (tmp_path / "scotsman-iver2.xtf").write_bytes(data[:1024 + 400 * packet + 99])
    got = userfiles.file_warnings({"observations": str(tmp_path / "m.csv"), "observations_sha256": "x"})
    assert got == [f"scotsman-iver2.xtf is truncated: the packet at byte {1024 + 400 * packet} is incomplete "
                   f"({packet - 99} bytes missing); read the 400 complete pings before it, the rest of the "
                   "recording is lost"]


def test_whole_files_and_other_runs_have_no_warning():
    whole = str((REAL / "scotsman_matches.csv").relative_to(REPO_ROOT))
    assert userfiles.file_warnings({"observations": whole, "observations_sha256": "x"}) == []
    sightings = str((DATA_DIR / "examples" / "your_pings" / "example_sightings.csv").relative_to(REPO_ROOT))
    assert userfiles.file_warnings({"observations": sightings, "observations_sha256": "x"}) == []
    assert userfiles.file_warnings({"seed": 1}) == []
