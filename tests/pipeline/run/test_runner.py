"""Running one notebook through papermill (sss_locus.pipeline.run.runner and the `sss-locus` command).

Uses a tiny throwaway notebook written to a temporary folder, executed into a temporary build
area (``SSS_LOCUS_BUILD_DIR``), so nothing of the real build is touched.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("papermill")
nbformat = pytest.importorskip("nbformat")

from notebook_support import write_notebook  # noqa: E402
from sss_locus.pipeline.cli import command as cli  # noqa: E402
from sss_locus.pipeline.run.registry import NotebookEntry, ParameterError  # noqa: E402
from sss_locus.pipeline.run.runner import KERNEL_NAME, NotebookFailed, is_up_to_date, run_notebook  # noqa: E402

PARAMETERS = "n: int = 3          # number of points\nscale = 1.5         # metres\nfail = False\n"
BODY = """\
import os, json, sys
import matplotlib.pyplot as plt
import pandas as pd
from sss_locus.pipeline.publish.export import export_figure
if fail:
    raise RuntimeError("asked to fail")
frame = pd.DataFrame({"i": range(n), "y_m": [scale * i for i in range(n)]})
fig, ax = plt.subplots()
ax.plot(frame["i"], frame["y_m"])
export_figure(fig, "fig-tiny-line", frame, caption="A line.", parameters={"n": n, "scale": scale})
from sss_locus.pipeline.publish.publish import publish
fig2, ax2 = plt.subplots()
ax2.plot(frame["i"], -frame["y_m"])
publish(fig2, "fig-tiny-published", frame, caption=f"The same line mirrored, {n} points.")
print(json.dumps({"n": n, "scale": scale, "cwd": os.getcwd(), "python": sys.executable,
                  "ipythondir": os.environ.get("IPYTHONDIR"), "mpl": os.environ.get("MPLCONFIGDIR"),
                  "blas": [os.environ.get(v) for v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")]}))
"""


def tiny_notebook(folder: Path) -> Path:
    return write_notebook(folder / "tiny.ipynb", PARAMETERS, BODY, markdown="# Tiny\n\nMath: $x^2$.")


@pytest.fixture
def entry(tmp_path):
    source = tiny_notebook(tmp_path)
    return NotebookEntry("tiny", source, "executed/tiny.ipynb", {"book": {}, "quick": {"n": 2}})


def _printed(executed: Path) -> dict:
    nb = json.loads(executed.read_text())
    for cell in nb["cells"]:
        for output in cell.get("outputs", []):
            if output.get("name") == "stdout":
                return json.loads("".join(output["text"]))
    raise AssertionError("no stdout in the executed notebook")


def test_run_with_profile_and_override(build_area, entry, monkeypatch):
    monkeypatch.setenv("OPENBLAS_NUM_THREADS", "8")  # the user's setting does not reach the kernel
    executed = run_notebook(entry, "quick", {"scale": "2"}, from_text=True, log=lambda *_: None)
    assert executed == build_area / "source" / "executed" / "tiny.ipynb"
    printed = _printed(executed)
    assert printed["n"] == 2 and printed["scale"] == 2.0
    # hermetic kernel: working directory and state folders inside the build area
    assert Path(printed["cwd"]) == executed.parent
    assert printed["ipythondir"].startswith(str(build_area)) and printed["mpl"].startswith(str(build_area))
    nb = json.loads(executed.read_text())
    assert nb["metadata"]["papermill"]["parameters"] == {"n": 2, "scale": 2.0, "fail": False}
    assert nb["metadata"]["sss_locus"]["profile"] == "quick"
    assert printed["python"] == sys.executable  # the project's kernel, not one from the home folder
    assert printed["blas"] == ["1", "1", "1"]  # numbers independent of the core count (runner.KERNEL_BLAS_THREADS)
    assert (build_area / "jupyter" / "data" / "kernels" / KERNEL_NAME / "kernel.json").is_file()
    injected = [c for c in nb["cells"] if "injected-parameters" in c["metadata"].get("tags", [])]
    assert len(injected) == 1
    assert "hide-input" in injected[0]["metadata"]["tags"]
    assert "n = 2" in "".join(injected[0]["source"])
    shown = "".join(next(c for c in nb["cells"] if "parameters" in c["metadata"].get("tags", []))["source"])
    assert shown.startswith("# The values this run used (profile 'quick')")  # the visible cell: the run's values
    assert re.search(r"^n: int = 2\b", shown, re.M) and re.search(r"^scale = 2.0\b", shown, re.M)
    manifest = json.loads((build_area / "source" / "_extra" / "figures" / "fig-tiny-line.json").read_text())
    assert manifest["parameters"] == {"n": 2, "scale": 2.0}
    assert manifest["profile"] == "quick" and manifest["notebook"] == entry.source_relative
    # publish() takes the run's resolved parameters from the runner (nothing retyped in the cell)
    published = json.loads((build_area / "source" / "_extra" / "figures" / "fig-tiny-published.json").read_text())
    assert published["parameters"] == {"n": 2, "scale": 2.0, "fail": False}
    assert published["caption"] == "The same line mirrored, 2 points."
    glued = {o["metadata"]["scrapbook"]["name"] for c in nb["cells"] if c["cell_type"] == "code"
             for o in c.get("outputs", []) if "scrapbook" in o.get("metadata", {})}
    assert {"fig-tiny-published", "fig-tiny-published-caption"} <= glued


def test_bad_parameter_stops_before_running(build_area, entry):
    with pytest.raises(ParameterError, match="(?s)no parameter 'm'.*n: int = 3  # number of points"):
        run_notebook(entry, "book", {"m": "1"}, from_text=True)
    with pytest.raises(ParameterError, match="parameter 'n' = 1.5 .*expected a value of type int"):
        run_notebook(entry, "book", {"n": "1.5"}, from_text=True)
    assert not (build_area / "source" / "executed").exists()


def test_failing_cell_raises_and_keeps_the_traceback_aside(build_area, entry):
    with pytest.raises(NotebookFailed, match="RuntimeError: asked to fail") as info:
        run_notebook(entry, "book", {"fail": True}, log=lambda *_: None)
    assert "raise RuntimeError" in str(info.value) and "\n" not in str(info.value)
    assert "Traceback" in info.value.traceback or "RuntimeError" in info.value.traceback
    # the failed notebook is kept outside the book source; no executed copy was made
    assert "asked to fail" in (build_area / "failed" / "tiny.ipynb").read_text()
    assert not (build_area / "source" / "executed" / "tiny.ipynb").exists()


def test_rerun_replaces_figures_and_up_to_date_needs_an_identical_run(build_area, entry):
    assert not is_up_to_date(entry, "quick")
    run_notebook(entry, "book", log=lambda *_: None)
    data = build_area / "source" / "_extra" / "figures" / "fig-tiny-line.csv"
    assert len(data.read_text().splitlines()) == 1 + 3
    assert is_up_to_date(entry, "book") and not is_up_to_date(entry, "quick")
    run_notebook(entry, "quick", log=lambda *_: None)
    assert len(data.read_text().splitlines()) == 1 + 2  # re-exported with the new parameters
    assert is_up_to_date(entry, "quick")
    assert not is_up_to_date(entry, "book")  # other parameters
    (build_area / "source" / "_extra" / "figures" / "fig-tiny-line.png").write_bytes(b"tampered")
    assert not is_up_to_date(entry, "quick")
    run_notebook(entry, "quick", log=lambda *_: None)
    assert is_up_to_date(entry, "quick")
    entry.source.write_text(entry.source.read_text().replace("A line.", "A straight line."))
    assert not is_up_to_date(entry, "quick")  # the notebook changed


def test_cli_reports_errors_without_traceback(build_area, capsys):
    assert cli.main(["run", "no-such-notebook"]) == 2
    err = capsys.readouterr().err
    assert "unknown notebook 'no-such-notebook'" in err and "Traceback" not in err


def test_console_script_is_installed():
    script = Path(sys.executable).with_name("sss-locus")
    result = subprocess.run([str(script), "--help"], capture_output=True, text=True, timeout=60)
    assert result.returncode == 0 and "run" in result.stdout and "book" in result.stdout


def test_plain_papermill_runs_a_notebook(build_area, entry, tmp_path):
    """`papermill SOURCE OUT -p NAME VALUE` works without the sss-locus runner."""
    out = tmp_path / "plain.ipynb"
    env = {"PATH": str(Path(sys.executable).parent), "HOME": str(tmp_path),
           "JUPYTER_DATA_DIR": str(tmp_path / "jupyter"), "MPLBACKEND": "Agg",
           "SSS_LOCUS_BUILD_DIR": str(build_area)}
    result = subprocess.run(
        [str(Path(sys.executable).with_name("papermill")), str(entry.source), str(out),
         "-p", "n", "5", "--cwd", str(tmp_path), "--no-progress-bar"],
        env=env, capture_output=True, text=True, timeout=300, stdin=subprocess.DEVNULL,
    )
    assert result.returncode == 0, result.stderr[-3000:]
    assert _printed(out)["n"] == 5
    assert not build_area.exists()  # a side run never writes into the build area
    manifest = json.loads((tmp_path / "figures" / "fig-tiny-line.json").read_text())  # beside the output
    assert manifest["notebook"] == "interactive" and manifest["parameters"]["n"] == 5
    # outside the runner, publish() says it does not know the run's parameters
    published = json.loads((tmp_path / "figures" / "fig-tiny-published.json").read_text())
    assert published["notebook"] == "interactive" and published["profile"] == "none"
    assert published["parameters"] == {}
