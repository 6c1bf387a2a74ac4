"""Regenerate the your-pings chapter's worked example (SYNTHETIC) in data/examples/your_pings/.

The sightings are made by the project's own simulator over a known terrain
(:mod:`sss_locus.experiments.your_pings.example`): the reconstruction chapter's survey layout and
``random`` terrain of ``data/terrain.toml``, the shipped AUV of ``data/platforms.toml`` at the
altitude of its survey rule (10 % of the sonar's range) with the navigation noise of
``data/noise.toml``. The local frame is placed at an invented position (70 W, 43 N, in the Gulf
of Maine); nothing here is a real survey. Usage, from the repository root::

    .venv/bin/python tools/make_your_pings_example.py

It writes example_sightings.csv, example.xtf, example_xtf_matches.csv and example_truth.csv
(the same bytes on every run: the seeds are fixed).
"""

from __future__ import annotations

from sss_locus.experiments.sonar_files.observations import LocalFrame
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.experiments.datamodel.terrain import load_terrain_config, terrain_from_config
from sss_locus.experiments.reconstruction.terrain_survey import SurveyLayout
from sss_locus.experiments.your_pings.example import write_example
from sss_locus.paths import DATA_DIR

FOLDER = DATA_DIR / "examples" / "your_pings"
PLATFORM = "auv"
TERRAIN = "random"
SEED = 7
N_FEATURES = 8


def main() -> None:
    platform = load_platform(PLATFORM, DATA_DIR / "platforms.toml")
    config = load_terrain_config(DATA_DIR / "terrain.toml")
    terrain = terrain_from_config(TERRAIN, config, extent_m=800.0, seed=SEED)
    altitude = platform.altitude_fraction_of_range * platform.sonar.max_range_m
    paths = write_example(FOLDER, platform, terrain, SurveyLayout(**config["survey"]), frame=LocalFrame(-70.0, 43.0),
                          n_features=N_FEATURES, altitude_m=altitude, seed=SEED)
    for p in paths.values():
        print(p.relative_to(DATA_DIR.parent), p.stat().st_size, "bytes")


if __name__ == "__main__":
    main()
