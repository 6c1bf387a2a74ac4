"""Citable figure export (sss_locus.pipeline.publish.export)."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from PIL import Image  # noqa: E402  (matplotlib dependency)

from sss_locus.pipeline.publish import provenance  # noqa: E402
from sss_locus.pipeline.publish.export import export_figure, load_manifests, remove_figures_of  # noqa: E402

DATA = pd.DataFrame({"alpha_rad": np.linspace(0, 1, 5), "z_m": np.linspace(-2, 2, 5)})


@pytest.fixture
def fig():
    figure, ax = plt.subplots(figsize=(3, 2))
    ax.plot(DATA["alpha_rad"], DATA["z_m"])
    yield figure
    plt.close(figure)


def test_all_files_and_manifest_are_written(tmp_path, fig, run_context):
    run_context(notebook="notebooks/concept.ipynb", profile="quick")
    manifest = export_figure(fig, "fig-demo-one", DATA, caption="Two spheres meet in a circle. Details.",
                             parameters={"n": np.int64(4), "seed": 7}, out_dir=tmp_path)
    names = {p.name for p in tmp_path.iterdir()}
    assert names == {f"fig-demo-one.{ext}" for ext in ("png", "svg", "pdf", "csv", "bib", "json")}
    on_disk = json.loads((tmp_path / "fig-demo-one.json").read_text())
    assert on_disk == manifest
    assert manifest["notebook"] == "notebooks/concept.ipynb" and manifest["profile"] == "quick"
    assert manifest["parameters"] == {"n": 4, "seed": 7} and manifest["seed"] == 7
    assert manifest["cell"] is None  # not run from a notebook cell
    for key in ("git_commit", "lock_sha256", "package_version", "run_time_utc", "caption"):
        assert manifest[key]
    assert manifest["lock_sha256"] == provenance.lock_sha256() != "missing"
    for name, entry in manifest["files"].items():
        assert entry["url"] == f"figures/{name}"
        assert entry["sha256"] == provenance.file_sha256(tmp_path / name)
    assert (tmp_path / "fig-demo-one.pdf").read_bytes().startswith(b"%PDF")
    assert b"<svg" in (tmp_path / "fig-demo-one.svg").read_bytes()


def test_png_resolution_and_csv_round_trip(tmp_path, fig):
    export_figure(fig, "fig-demo", DATA, caption="C.", parameters={}, dpi=250, out_dir=tmp_path)
    with Image.open(tmp_path / "fig-demo.png") as image:
        assert image.info["dpi"][0] == pytest.approx(250, abs=1)
    pd.testing.assert_frame_equal(pd.read_csv(tmp_path / "fig-demo.csv"), DATA)


def test_dict_of_frames_gives_one_csv_each(tmp_path, fig):
    other = pd.DataFrame({"x": [1, 2]}, index=pd.Index(["a", "b"], name="platform"))
    manifest = export_figure(fig, "fig-demo", {"arcs": DATA, "sensors": other}, caption="C.",
                             parameters={}, out_dir=tmp_path)
    assert {"fig-demo--arcs.csv", "fig-demo--sensors.csv"} <= set(manifest["files"])
    back = pd.read_csv(tmp_path / "fig-demo--sensors.csv", index_col="platform")
    pd.testing.assert_frame_equal(back, other)


def test_vector_files_do_not_change_between_identical_runs(tmp_path, fig):
    first = export_figure(fig, "fig-demo", DATA, caption="C.", parameters={}, out_dir=tmp_path)
    second = export_figure(fig, "fig-demo", DATA, caption="C.", parameters={}, out_dir=tmp_path)
    for name in ("fig-demo.svg", "fig-demo.pdf", "fig-demo.png", "fig-demo.csv"):
        assert first["files"][name]["sha256"] == second["files"][name]["sha256"]


def test_bibtex_entry(tmp_path, fig):
    export_figure(fig, "fig-demo", DATA, caption="Locus of $\\theta_1$ & width_m at 50% range. More text.",
                  parameters={}, out_dir=tmp_path)
    bib = (tmp_path / "fig-demo.bib").read_text()
    assert bib.startswith("@misc{sss-locus:fig-demo,")
    assert "title = {{Figure fig-demo: Locus of $\\theta_1$ \\& width\\_m at 50\\% range}}" in bib
    assert "More text" not in bib
    assert bib.count("{") == bib.count("}")


@pytest.mark.parametrize("label", ["locus", "fig_locus", "fig-Locus", "fig--locus", "fig-", 3])
def test_bad_label_is_rejected(tmp_path, fig, label):
    with pytest.raises(ValueError, match="label must look like"):
        export_figure(fig, label, DATA, caption="C.", parameters={}, out_dir=tmp_path)


@pytest.mark.parametrize("kwargs, fragment", [
    ({"dpi": 150}, "dpi must be"),
    ({"caption": "  "}, "caption must be"),
    ({"parameters": [1]}, "parameters must be a mapping"),
    ({"data": [1, 2]}, "data must be a pandas DataFrame"),
    ({"data": {}}, "data must be a pandas DataFrame"),
    ({"data": {"Bad Name": DATA}}, "data keys"),
    ({"parameters": {"f": object()}}, "not JSON-like"),
])
def test_bad_arguments_are_rejected(tmp_path, fig, kwargs, fragment):
    args = {"data": DATA, "caption": "C.", "parameters": {}, "out_dir": tmp_path, **kwargs}
    with pytest.raises(ValueError, match=fragment):
        export_figure(fig, "fig-demo", **args)
    assert not (tmp_path / "fig-demo.json").exists()


def test_not_a_figure_is_rejected(tmp_path):
    with pytest.raises(ValueError, match="matplotlib Figure"):
        export_figure("figure", "fig-demo", DATA, caption="C.", parameters={}, out_dir=tmp_path)


def test_load_manifests_skips_incomplete_or_tampered_figures(tmp_path, fig):
    for label in ("fig-a", "fig-b", "fig-c"):
        export_figure(fig, label, DATA, caption="C.", parameters={}, notebook="nb.ipynb", out_dir=tmp_path)
    (tmp_path / "fig-b.csv").write_text("x\n1\n")  # data no longer matches the manifest
    (tmp_path / "fig-c.png").unlink()
    assert [m["label"] for m in load_manifests(tmp_path)] == ["fig-a"]


def test_remove_figures_of_one_notebook_only(tmp_path, fig):
    export_figure(fig, "fig-a", DATA, caption="C.", parameters={}, notebook="one.ipynb", out_dir=tmp_path)
    export_figure(fig, "fig-b", DATA, caption="C.", parameters={}, notebook="two.ipynb", out_dir=tmp_path)
    assert remove_figures_of("one.ipynb", tmp_path) == ["fig-a"]
    assert sorted(p.name for p in tmp_path.iterdir() if p.name.startswith("fig-a")) == []
    assert [m["label"] for m in load_manifests(tmp_path)] == ["fig-b"]


def test_default_folder_is_beside_the_run_never_the_build_area(tmp_path, fig, monkeypatch, run_context):
    """Outside the runner (plain papermill, interactive) figures go to figures/ in the working
    directory (papermill --cwd: the output's folder); the runner points them at its staging."""
    monkeypatch.setenv("SSS_LOCUS_BUILD_DIR", str(tmp_path / "build"))
    monkeypatch.chdir(tmp_path)
    export_figure(fig, "fig-demo", DATA, caption="C.", parameters={})
    assert (tmp_path / "figures" / "fig-demo.png").is_file()
    assert not (tmp_path / "build").exists()
    run_context(figures_dir=tmp_path / "staging")
    export_figure(fig, "fig-demo", DATA, caption="C.", parameters={})
    assert (tmp_path / "staging" / "fig-demo.json").is_file()
    assert not [p for p in tmp_path.rglob("*") if ".tmp-" in p.name]  # no temporary file left


def test_manifest_vanishing_mid_scan_is_skipped(tmp_path, fig, monkeypatch):
    """Notebooks built in parallel delete and rewrite their own figures: a manifest listed by
    glob may be gone when it is read. Neither scan may crash on that (seen with --jobs 2)."""
    export_figure(fig, "fig-demo-kept", DATA, caption="Kept.", parameters={}, out_dir=tmp_path)
    ghost = tmp_path / "fig-demo-ghost.json"  # listed, but never on disk
    real_glob = type(tmp_path).glob
    monkeypatch.setattr(type(tmp_path), "glob",
                        lambda self, pattern: [*real_glob(self, pattern), ghost])
    assert [m["label"] for m in load_manifests(tmp_path)] == ["fig-demo-kept"]
    assert remove_figures_of("no-such-notebook", tmp_path) == []


def _laid_out_figure():
    figure, axs = plt.subplots(1, 2, figsize=(5, 2.5), constrained_layout=True)
    image = axs[0].imshow(np.arange(12.0).reshape(3, 4))
    figure.colorbar(image, ax=axs[0], label="value (m)")
    axs[1].plot(DATA["alpha_rad"], DATA["z_m"], label="z")
    axs[1].set_xlabel("alpha (rad)")
    axs[1].legend()
    figure.suptitle("one layout")
    return figure


def test_one_layout_gives_matplotlibs_png_and_the_same_box_for_every_format(tmp_path):
    """The PNG is byte for byte what a plain ``savefig(bbox_inches="tight")`` writes (reference:
    matplotlib itself, on an identical figure); the SVG, PDF and the shown picture are drawn with
    the same layout and tight box (the same size in inches), and the layout engine is kept."""
    import io
    import re

    reference, figure = _laid_out_figure(), _laid_out_figure()
    buffer = io.BytesIO()
    reference.savefig(buffer, format="png", dpi=300, bbox_inches="tight")
    engine = figure.get_layout_engine()
    shown = []
    export_figure(figure, "fig-demo", DATA, caption="C.", parameters={}, out_dir=tmp_path, shown=shown)
    assert figure.get_layout_engine() is engine
    plt.close(reference)
    plt.close(figure)
    assert (tmp_path / "fig-demo.png").read_bytes() == buffer.getvalue()
    with Image.open(tmp_path / "fig-demo.png") as png, Image.open(io.BytesIO(shown[0])) as small:
        width_in = png.size[0] / 300
        assert small.size[0] == pytest.approx(width_in * figure.dpi, abs=1)
    svg_pt = float(re.search(rb'<svg[^>]*width="([0-9.]+)pt"', (tmp_path / "fig-demo.svg").read_bytes()).group(1))
    pdf_box = re.search(rb"/MediaBox \[\s*0 0 ([0-9.]+) ", (tmp_path / "fig-demo.pdf").read_bytes())
    assert svg_pt / 72 == pytest.approx(width_in, abs=1 / 300 + 1e-3)
    assert float(pdf_box.group(1)) / 72 == pytest.approx(width_in, abs=1 / 300 + 1e-3)
