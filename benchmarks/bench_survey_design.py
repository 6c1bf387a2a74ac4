"""Survey design over a km-scale area at the book profile, on one thread (CPU time).

A 5 km x 5 km square (an origin near Utah Lake, water 30 m deep), each platform of the book, the
survey-design chapter's book-profile parameters (``notebooks/survey_design.ipynb``'s defaults:
the search grid, 200 features, a 20 m coverage grid, five noise seeds, the eight leading plans
scored): the search (:func:`~sss_locus.experiments.survey_design.front.search_plans`) and the scoring
of the candidates with the joint adjustment under the noise model
(:func:`~sss_locus.experiments.survey_design.scoring.score_plans`), timed separately, without the
cache, with peak memory (``ru_maxrss``). Also the one-line case: a 260 m x 200 m area planned end
to end.

    python benchmarks/bench_survey_design.py            # 5 km x 5 km
    python benchmarks/bench_survey_design.py --km 1     # a 1 km square: a few seconds
    python benchmarks/bench_survey_design.py --seeds 3 --n-scored 4   # the scoring's sizes
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMEXPR_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402
import platform as _platform  # noqa: E402
import resource  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

BOOK = dict(headings_deg=[0.0, 45.0, 90.0], spacing_fractions=[0.8, 1.2, 1.6],
            crossing_angles_deg=[math.nan, 0.0, 20.0, 45.0, 90.0], cross_spacing_factors=[1.0, 2.0],
            altitude_fractions=[0.08, 0.14], pitches_deg=[0.0])
"""The notebook's book-profile grid (``no_cross_lines = True`` adds NaN)."""


def main() -> None:
    from sss_locus.experiments.survey_design import front as sd
    from sss_locus.experiments.noise.study import load_noise_model, load_pass_noise
    from sss_locus.experiments.datamodel.platforms import load_platform
    from sss_locus.experiments.survey_design.area import area_from_vertices, with_water_depth
    from sss_locus.experiments.survey_design import scoring

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--km", type=float, default=5.0, help="side of the square area, km")
    ap.add_argument("--platforms", default="boat,auv")
    ap.add_argument("--seeds", type=int, default=5, help="noise seeds (the book profile's five)")
    ap.add_argument("--n-scored", type=int, default=8, help="leading plans scored (the book profile's n_scored)")
    args = ap.parse_args()
    side = 1000.0 * args.km
    area = with_water_depth(area_from_vertices([[0, 0], [side, 0], [side, side], [0, side]], name=f"{args.km:g} km square",
                                               origin_lonlat=(-111.81, 40.234)), 30.0, "benchmark")
    print(f"{args.km:g} km x {args.km:g} km, book profile, one thread; CPU {_platform.processor() or _platform.machine()}, "
          f"numpy {np.__version__}")
    print(f"{args.seeds} noise seeds, n_scored {args.n_scored}")
    print("| platform | plans | scored | search (s CPU) | joint scoring (s CPU) | total (s CPU) | peak RSS (MB) | recommended |")
    print("|---|---|---|---|---|---|---|---|")
    for key in args.platforms.split(","):
        pf = load_platform(key)
        t0 = time.process_time()
        plans = sd.search_plans(pf, area.key(), "flat", "locus", BOOK, n_features=200, seed=1, grid_m=20.0)
        t1 = time.process_time()
        scores = scoring.score_plans(pf, area.key(), "flat", plans, load_noise_model(key), load_pass_noise(key),
                                     seeds=list(range(1, args.seeds + 1)), n_features=200, grid_m=20.0,
                                     objective_col="locus_median_m", n_scored=args.n_scored)
        verdict = scoring.recommend_under_noise(scoring.summarise(scores))
        t2 = time.process_time()
        rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
        print(f"| {key} | {len(plans)} | {scores.plan_index.nunique()} | {t1 - t0:.1f} | {t2 - t1:.1f} | {t2 - t0:.1f} "
              f"| {rss:.0f} | {verdict['reason']} |", flush=True)
    small = with_water_depth(area_from_vertices([[0, 0], [260, 0], [260, 200], [0, 200]], name="pond"), 30.0, "benchmark")
    ones = [int((sd.search_plans(load_platform(k), small.key(), "flat", "locus", BOOK, n_features=200, seed=1,
                                 grid_m=20.0).n_segments == 1).sum()) for k in args.platforms.split(",")]
    print(json.dumps({"one_line_area_plans_with_one_segment": ones}))


if __name__ == "__main__":
    main()
