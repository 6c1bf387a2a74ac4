"""The run context (sss_locus.pipeline.run.context): one file between a run's processes, not variables.

A tiny notebook run for real shows what its kernel sees: ``SSS_LOCUS_RUN`` and no other
``SSS_LOCUS_*`` variable (even with stale ones in the parent's environment), the run's notebook,
profile, parameters, run key and figures folder from the context, and the data entries its
loaders read written back by the pipeline into the executed copy.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from sss_locus import paths
from sss_locus.pipeline.run import context

pytest.importorskip("papermill")

from notebook_support import write_notebook  # noqa: E402
from sss_locus.pipeline.run.registry import NotebookEntry  # noqa: E402
from sss_locus.pipeline.run.runner import kernel_environment, run_notebook  # noqa: E402

PARAMETERS = "n: int = 3  # points\ndata_files: list = []  # data files\ndata_set: list = []  # overrides\n"
BODY = """\
import json, os
from sss_locus.experiments.datamodel import userdata
from sss_locus.experiments.datamodel.platforms import load_platform
from sss_locus.pipeline.run import context
userdata.use(data_files, data_set)
load_platform("auv")
ctx = context.current()
print(json.dumps({"env": sorted(k for k in os.environ if k.startswith("SSS_LOCUS_")),
                  "notebook": ctx.notebook, "profile": ctx.profile, "n": ctx.parameters["n"],
                  "run_key": ctx.run_key, "figures": str(ctx.figures_dir), "build": str(ctx.build_dir)}))
"""


def test_the_context_round_trips_through_its_file(tmp_path):
    ctx = context.from_environment({}).replace(notebook="notebooks/x.ipynb", profile="quick", run_key="k",
                                               parameters={"seed": 1, "platforms": ["auv"]},
                                               figures_dir=tmp_path / "f", quiet_batches=True)
    assert context.load(context.write(ctx, tmp_path)) == ctx
    (tmp_path / "bad.json").write_text('{"build_dir": "/b", "cache_dir": "/c", "caller_dir": "/", "color": 1}')
    with pytest.raises(ValueError, match=r"SSS_LOCUS_RUN=.*bad.json: cannot read the run context .*'color'"):
        context.load(tmp_path / "bad.json")


def test_current_is_the_innermost_block_then_the_file_then_the_users_settings(tmp_path, monkeypatch):
    monkeypatch.delenv(context.RUN_ENV, raising=False)
    monkeypatch.setenv(paths.BUILD_DIR_ENV, str(tmp_path / "mine"))
    monkeypatch.setenv("SSS_LOCUS_SCHEDULER", "local:1")
    assert paths.build_dir() == tmp_path / "mine" and context.current().scheduler == "local:1"
    assert context.current().notebook == "interactive" and context.current().run_key is None
    filed = context.current().replace(build_dir=tmp_path / "filed", profile="quick")
    monkeypatch.setenv(context.RUN_ENV, str(context.write(filed, tmp_path / "run")))
    assert context.current() == filed and paths.build_dir() == tmp_path / "filed"
    with context.use(filed.replace(build_name="named")):
        assert paths.build_name() == "named"
        context.amend(reproduction_checked=True)
        assert context.current().reproduction_checked
    assert paths.build_name() is None and not context.current().reproduction_checked


def test_the_kernel_gets_one_variable_and_reads_its_run_from_the_file(build_area, tmp_path, monkeypatch):
    monkeypatch.setenv("SSS_LOCUS_PROFILE", "stale")  # a variable of the old channel: never passed on
    staging = tmp_path / "staging"
    env = kernel_environment(staging)
    assert [k for k in env if k.startswith("SSS_LOCUS_")] == [context.RUN_ENV]
    source = write_notebook(tmp_path / "ctx.ipynb", PARAMETERS, BODY)
    entry = NotebookEntry("ctx", source, "executed/ctx.ipynb", {"book": {}, "quick": {"n": 2}})
    mine = tmp_path / "mine.toml"
    mine.write_text((paths.DATA_DIR / "examples" / "my_auv.toml").read_text())
    data = __import__("sss_locus.experiments.datamodel.userdata", fromlist=["x"]).make_inputs([str(mine)], [])
    executed = run_notebook(entry, "quick", log=lambda *_: None, data=data)
    nb = json.loads(executed.read_text())
    printed = next(json.loads("".join(o["text"])) for c in nb["cells"] for o in c.get("outputs", [])
                   if o.get("name") == "stdout" and "run_key" in "".join(o["text"]))
    record = nb["metadata"]["sss_locus"]
    assert printed["env"] == [context.RUN_ENV]
    assert printed["profile"] == "quick" and printed["n"] == 2 and printed["run_key"] == record["run_key"]
    assert Path(printed["build"]) == build_area and Path(printed["figures"]).parent.parent == build_area / "tmp"
    # the loaders' reads, recorded in memory and written back by the kernel after each cell
    auv_sonar = __import__("tomllib").loads((paths.DATA_DIR / "platforms.toml").read_text())["platforms"]["auv"]
    assert set(record["data_read"]) == {"platforms.auv", f"sonars.{auv_sonar['sonar']}"}
