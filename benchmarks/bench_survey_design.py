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
    python benchmarks/bench_survey_design.py --baseline fda8de6       # old and new side by side

``--baseline REF`` measures the same on ``REF`` too, in the same run (``git archive REF`` into a
temporary folder, run in a child process with that tree first on ``PYTHONPATH``; CPU time of the
child's own ``time.process_time()``), and says whether both trees' plans tables and scores are
identical.
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
import sys  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

BOOK = dict(headings_deg=[0.0, 45.0, 90.0], spacing_fractions=[0.8, 1.2, 1.6],
            crossing_angles_deg=[math.nan, 0.0, 20.0, 45.0, 90.0], cross_spacing_factors=[1.0, 2.0],
            altitude_fractions=[0.08, 0.14], pitches_deg=[0.0])
"""The notebook's book-profile grid (``no_cross_lines = True`` adds NaN)."""


def _modules():
    """The modules measured, in this tree's rooms or, for a ``--baseline`` tree from before the
    move into rooms (issue 41), at their old flat paths."""
    try:
        from sss_locus.experiments.datamodel.platforms import load_platform
        from sss_locus.experiments.datamodel.noise_model import load_noise_model
        from sss_locus.experiments.passes.pass_noise import load_pass_noise
        from sss_locus.experiments.survey_design import front as sd, scoring
        from sss_locus.experiments.survey_design.area import area_from_vertices, with_water_depth
    except ImportError:  # a tree before the rooms
        from sss_locus.experiments import survey_design as sd
        from sss_locus.experiments.noise import load_noise_model, load_pass_noise
        from sss_locus.experiments.platforms import load_platform
        from sss_locus.experiments.survey_area import area_from_vertices, with_water_depth
        from sss_locus.experiments.surveydesign import scoring
    return sd, scoring, load_platform, area_from_vertices, with_water_depth, load_noise_model, load_pass_noise


def measure(key: str, km: float, seeds: int, n_scored: int) -> dict:
    """Search and joint scoring of platform ``key`` on the ``km`` square: CPU seconds, the
    verdict, and a digest of the plans table and the scores (to compare two trees)."""
    import hashlib

    sd, scoring, load_platform, area_from_vertices, with_water_depth, load_noise_model, load_pass_noise = _modules()

    side = 1000.0 * km
    area = with_water_depth(area_from_vertices([[0, 0], [side, 0], [side, side], [0, side]], name=f"{km:g} km square",
                                               origin_lonlat=(-111.81, 40.234)), 30.0, "benchmark")
    pf = load_platform(key)
    t0 = time.process_time()
    plans = sd.search_plans(pf, area.key(), "flat", "locus", BOOK, n_features=200, seed=1, grid_m=20.0)
    t1 = time.process_time()
    scores = scoring.score_plans(pf, area.key(), "flat", plans, load_noise_model(key), load_pass_noise(key),
                                 seeds=list(range(1, seeds + 1)), n_features=200, grid_m=20.0,
                                 objective_col="locus_median_m", n_scored=n_scored)
    verdict = scoring.recommend_under_noise(scoring.summarise(scores))
    t2 = time.process_time()
    digest = lambda df: hashlib.sha256(df.to_csv(index=False).encode()).hexdigest()[:12]  # noqa: E731
    return {"plans": len(plans), "scored": int(scores.plan_index.nunique()), "search_s": t1 - t0, "scoring_s": t2 - t1,
            "rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, "reason": verdict["reason"],
            "plans_digest": digest(plans), "scores_digest": digest(scores)}


def baseline(ref: str, key: str, args) -> dict:
    """:func:`measure` on ``git archive ref`` in a child process (module docstring)."""
    import subprocess
    import tempfile
    from pathlib import Path

    repo = Path(__file__).resolve().parents[1]
    with tempfile.TemporaryDirectory() as tmp:
        tar = subprocess.run(["git", "archive", ref], cwd=repo, check=True, capture_output=True).stdout
        subprocess.run(["tar", "-x", "-C", tmp], input=tar, check=True)
        env = dict(os.environ, PYTHONPATH=tmp)
        out = subprocess.run([sys.executable, str(Path(__file__).resolve()), "--child", key, "--km", str(args.km),
                              "--seeds", str(args.seeds), "--n-scored", str(args.n_scored)], cwd=tmp, env=env,
                             check=True, capture_output=True, text=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def main() -> None:
    sd, _, load_platform, area_from_vertices, with_water_depth, _, _ = _modules()

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--km", type=float, default=5.0, help="side of the square area, km")
    ap.add_argument("--platforms", default="boat,auv")
    ap.add_argument("--seeds", type=int, default=5, help="noise seeds (the book profile's five)")
    ap.add_argument("--n-scored", type=int, default=8, help="leading plans scored (the book profile's n_scored)")
    ap.add_argument("--baseline", default=None, help="a git ref measured side by side (module docstring)")
    ap.add_argument("--child", default=None, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        print(json.dumps(measure(args.child, args.km, args.seeds, args.n_scored)))
        return
    print(f"{args.km:g} km x {args.km:g} km, book profile, one thread; CPU {_platform.processor() or _platform.machine()}, "
          f"numpy {np.__version__}")
    print(f"{args.seeds} noise seeds, n_scored {args.n_scored}")
    print(f"load average at start {os.getloadavg()[0]:.2f}")
    print("| tree | platform | plans | scored | search (s CPU) | joint scoring (s CPU) | total (s CPU) | peak RSS (MB) "
          "| recommended |")
    print("|---|---|---|---|---|---|---|---|---|")
    same = []
    for key in args.platforms.split(","):
        runs = [("this tree", measure(key, args.km, args.seeds, args.n_scored))]
        if args.baseline:
            runs.append((f"baseline {args.baseline}", baseline(args.baseline, key, args)))
            same.append((key, runs[0][1]["plans_digest"] == runs[1][1]["plans_digest"],
                         runs[0][1]["scores_digest"] == runs[1][1]["scores_digest"]))
        for tree, m in runs:
            print(f"| {tree} | {key} | {m['plans']} | {m['scored']} | {m['search_s']:.1f} | {m['scoring_s']:.1f} "
                  f"| {m['search_s'] + m['scoring_s']:.1f} | {m['rss_mb']:.0f} | {m['reason']} |", flush=True)
    for key, plans_same, scores_same in same:
        print(f"{key}: plans table identical {plans_same}, scores identical {scores_same}")
    print(f"load average at end {os.getloadavg()[0]:.2f}")
    small = with_water_depth(area_from_vertices([[0, 0], [260, 0], [260, 200], [0, 200]], name="pond"), 30.0, "benchmark")
    ones = [int((sd.search_plans(load_platform(k), small.key(), "flat", "locus", BOOK, n_features=200, seed=1,
                                 grid_m=20.0).n_segments == 1).sum()) for k in args.platforms.split(",")]
    print(json.dumps({"one_line_area_plans_with_one_segment": ones}))


if __name__ == "__main__":
    main()
