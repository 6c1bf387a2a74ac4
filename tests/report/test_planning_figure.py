"""The planning chapter's figure and summary with more platforms than the paper's two
(issue 37: panel titles overlapped with three platforms; the summary listed only Boat and AUV)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")

from sss_locus.experiments.datamodel.envelopes import OffsetModel  # noqa: E402
from sss_locus.experiments.survey_passes.planning import planning_bands  # noqa: E402
from sss_locus.experiments.datamodel.platforms import load_platforms  # noqa: E402
from sss_locus.report.survey_passes import planning  # noqa: E402

SPECS = ("independent", "matched:10:same")


def _curves(names):
    """Hand-made curves (a hump at 60° for each platform): what the figure draws, not a simulation."""
    g = np.arange(0.0, 181.0, 5.0)
    curves = {}
    for i, (key, name) in enumerate(names.items()):
        for spec in SPECS:
            med = 10 + (i + 1) * np.exp(-((g - 60) / 30) ** 2)
            frame = pd.DataFrame({"crossing_angle_deg": g, "locus_length_m_median": med,
                                  "locus_length_m_q25": med - 1, "locus_length_m_q75": med + 1})
            curves[(key, spec)] = SimpleNamespace(curve=frame, platform=SimpleNamespace(name=name),
                                                  offset_model=OffsetModel.parse(spec))
    return curves, {ks: planning_bands(c.curve) for ks, c in curves.items()}


def _overlaps(fig):
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    boxes = [ax.title.get_window_extent(renderer) for ax in fig.axes if ax.get_title()]
    return [(a, b) for i, a in enumerate(boxes) for b in boxes[i + 1:] if a.overlaps(b)], boxes


def test_panel_titles_do_not_overlap_with_three_platforms():
    shipped = {k: p.name for k, p in load_platforms().items()}
    names = {**shipped, "myboat": "My BlueBoat, Cerulean Omniscan 450 SS, 20° tilt"}
    curves, bands = _curves(names)
    fig = planning.plot_planning_bands(curves, bands)
    overlaps, boxes = _overlaps(fig)
    assert len(boxes) == 6 and not overlaps
    width = fig.get_size_inches()[0] * fig.dpi
    assert all(0 <= b.x0 and b.x1 <= width for b in boxes)  # inside the figure too
    titles = [ax.get_title().replace("\n", " ") for ax in fig.axes if ax.get_title()]
    assert any("My BlueBoat, Cerulean Omniscan 450 SS, 20° tilt" in t for t in titles)  # wrapped, not cut


def test_summary_table_lists_every_platform_of_the_run():
    names = {"boat": "Surface boat", "auv": "Torpedo AUV", "myboat": "My BlueBoat"}
    curves, bands = _curves(names)
    text = planning.bands_markdown(curves, bands)
    rows = [line for line in text.splitlines() if line.startswith("| ") and "---" not in line]
    assert len(rows) == 1 + 2 * 3 + 1  # header, every platform under both offset models, the paper
    for name in names.values():
        assert sum(name in r for r in rows) == 2
    assert "Paper (Sec. IV-D)" in rows[-1]
