"""Readability of published figures (sss_locus.pipeline.publish.readability): which text is counted and
how large it appears in the book's column. Every figure of the book is checked against the
threshold in ``test_book_build.py::test_every_published_figure_is_readable_at_the_column_width``.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from PIL import Image  # noqa: E402  (matplotlib dependency)

from sss_locus.pipeline.publish import readability  # noqa: E402
from sss_locus.pipeline.publish.export import export_figure  # noqa: E402


def _drawn(fig):
    with readability.recording_text() as drawn:
        fig.canvas.draw()
    return drawn


def test_every_kind_of_drawn_text_is_recorded_with_its_size():
    fig, ax = plt.subplots(figsize=(4, 3))
    image = ax.imshow(np.arange(6.0).reshape(2, 3))
    colorbar = fig.colorbar(image)
    colorbar.ax.tick_params(labelsize=5.5)
    ax.plot([0, 1], [0, 1], label="legend text")
    ax.legend(fontsize=6.5)
    ax.annotate("note", (0.5, 0.5), fontsize=7.5)
    ax.set_title("title", fontsize=11)
    ax.text(0, 0, "$\\psi_1$", fontsize=8.5)  # mathtext
    sizes = {(d["text"], d["size_pt"]) for d in _drawn(fig)}
    plt.close(fig)
    for item in (("legend text", 6.5), ("note", 7.5), ("title", 11.0), ("$\\psi_1$", 8.5)):
        assert item in sizes
    assert 5.5 in {s for _, s in sizes}  # colour-bar tick labels


def test_hidden_empty_and_out_of_view_text_is_not_counted():
    fig, (ax, off) = plt.subplots(1, 2, figsize=(4, 2))
    ax.set_xticks([0.0, 0.5, 5.0], ["a", "b", "far away"], fontsize=4)
    ax.set_xlim(0, 1)  # tick 5.0 is now outside the view
    ax.set_yticks([])
    ax.text(0.1, 0.1, "hidden", fontsize=3, visible=False)
    ax.text(0.1, 0.1, "   ", fontsize=2)
    off.axis("off")
    off.set_xticks([0.5], ["never drawn"], fontsize=1)
    texts = {d["text"] for d in _drawn(fig)}
    plt.close(fig)
    assert {"a", "b"} <= texts
    assert not texts & {"far away", "hidden", "   ", "never drawn"}


def test_rendered_size_follows_the_shown_picture():
    """Independent of the formula's inches: draw the picture a chapter shows (figure dpi, tight
    box), read its pixel width, scale it into the column as the browser does (never wider than
    the column, never enlarged) and convert the font size with the picture's pixels per point."""
    for width_in in (3.0, 6.0, 9.0, 14.0):
        fig, ax = plt.subplots(figsize=(width_in, 2.5), dpi=100)
        ax.set_title("x", fontsize=10)
        from io import BytesIO

        buffer = BytesIO()
        fig.savefig(buffer, format="png", bbox_inches="tight")
        plt.close(fig)
        natural_px = Image.open(buffer).size[0]
        shown_px = min(natural_px, readability.CONTENT_WIDTH_PX)
        expected = 10 / 72 * 100 * shown_px / natural_px
        assert readability.rendered_px(10, natural_px / 100, 100) == pytest.approx(expected, rel=1e-9)


def test_export_records_the_smallest_text_and_picture_width(tmp_path):
    fig, ax = plt.subplots(figsize=(8, 3))
    ax.plot([0, 1], [0, 1])
    ax.tick_params(labelsize=7)
    ax.set_xlabel("angle (deg)", fontsize=12)
    manifest = export_figure(fig, "fig-demo", pd.DataFrame({"x": [0, 1]}), caption="C.",
                             parameters={}, out_dir=tmp_path)
    plt.close(fig)
    text = manifest["text"]
    assert text["min_size_pt"] == 7.0 and text["dpi"] == fig.dpi
    with Image.open(tmp_path / "fig-demo.png") as image:
        assert text["width_in"] == pytest.approx(image.size[0] / manifest["dpi"], abs=1e-3)
    assert 4 < text["width_in"] <= 8.2  # the tight box of an 8-inch figure (pad 0.1 in)
    assert readability.smallest_text_px(manifest) == pytest.approx(
        7 / 72 * min(fig.dpi, readability.CONTENT_WIDTH_PX / text["width_in"]))


@pytest.mark.parametrize("kwargs", [dict(size_pt=0, width_in=1, dpi=1), dict(size_pt=1, width_in=-1, dpi=1),
                                    dict(size_pt=1, width_in=1, dpi=float("nan"))])
def test_bad_sizes_are_rejected(kwargs):
    with pytest.raises(ValueError, match=next(k for k, v in kwargs.items() if not v > 0)):
        readability.rendered_px(**kwargs)


def test_manifest_without_a_text_record_is_an_error():
    with pytest.raises(ValueError, match="rerun its notebook"):
        readability.smallest_text_px({"label": "fig-old"})
