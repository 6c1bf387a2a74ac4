"""The programs of a notebook run (sss_locus.pipeline.run.kernels): the kernel of the ``sss-locus``
kernelspec behaves as ``python -m ipykernel_launcher`` does, runs every exit handler and skips the
interpreter's final garbage collection; the papermill process never imports pyarrow."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

pytest.importorskip("papermill")
pytest.importorskip("nbformat")
from jupyter_client import KernelManager  # noqa: E402
from jupyter_client.kernelspec import KernelSpecManager  # noqa: E402

from notebook_support import write_notebook  # noqa: E402
from sss_locus.pipeline.run import kernels  # noqa: E402

EXIT_PROBE = """\
import atexit, pathlib
out = pathlib.Path({out!r})
class Finalised:
    def __init__(self, path):
        self.path = path
    def __del__(self, open=open):  # its own open: the module is torn down by then
        open(self.path, "w").write("collected at exit")
a, b = Finalised(str(out / "finalised")), Finalised(str(out / "finalised"))
a.other, b.other = b, a  # a reference cycle that only a garbage collection can free...
keep = a  # ...alive until the interpreter tears down this namespace at exit
del b
atexit.register(lambda: (out / "exit-handler").write_text("ran"))
import mod_in_cwd  # the kernel's working directory is importable, as with ipykernel_launcher
(out / "path").write_text(repr(sys.path.index("")) if "" in sys.path else "absent")
"""


def _kernel(cwd):
    """A kernel of the ``sss-locus`` kernelspec (installed into the test's build area) in ``cwd``."""
    folder = kernels.install_kernelspec()
    km = KernelManager(kernel_name=kernels.KERNEL_NAME,
                       kernel_spec_manager=KernelSpecManager(kernel_dirs=[str(folder.parent)]))
    km.start_kernel(cwd=str(cwd))
    kc = km.client()
    kc.start_channels()
    kc.wait_for_ready(timeout=60)
    return km, kc


def test_kernel_runs_exit_handlers_and_skips_the_final_collection(build_area, tmp_path):
    cwd = tmp_path / "cwd"
    cwd.mkdir()
    (cwd / "mod_in_cwd.py").write_text("VALUE = 1\n")
    km, kc = _kernel(cwd)
    try:
        reply = kc.execute_interactive("import sys\n" + EXIT_PROBE.format(out=str(tmp_path)), timeout=60)
        assert reply["content"]["status"] == "ok", reply["content"]
    finally:
        kc.stop_channels()
        km.shutdown_kernel()  # graceful, as papermill's
    assert not km.is_alive()
    assert (tmp_path / "exit-handler").read_text() == "ran"  # the libraries' exit handlers still run
    assert (tmp_path / "path").read_text() != "absent"
    # the cycle was not collected at exit: the final collections skipped the frozen objects
    assert not (tmp_path / "finalised").exists()


def test_papermill_process_runs_a_notebook_without_importing_pyarrow(build_area, tmp_path):
    folder = kernels.install_kernelspec()
    notebook = write_notebook(tmp_path / "nb.ipynb", "n = 1\n", "print(n + 1)")
    args = tmp_path / "args.json"
    args.write_text(json.dumps({"input_path": str(notebook), "output_path": str(tmp_path / "out.ipynb"),
                                "parameters": {"n": 4}, "kernel_name": kernels.KERNEL_NAME,
                                "progress_bar": False, "log_output": False}))
    env = {**kernels.hermetic_env(), "JUPYTER_PATH": str(folder.parent.parent)}
    result = subprocess.run([sys.executable, "-X", "importtime", "-c", kernels.PAPERMILL_CHILD, str(args)],
                            capture_output=True, text=True, env={**os.environ, **env}, timeout=300)
    assert result.returncode == 0, result.stderr[-2000:]
    imported = [line.rsplit("|", 1)[-1].strip() for line in result.stderr.splitlines() if line.startswith("import time:")]
    assert "papermill" in imported and "pyarrow" not in imported and "numpy" not in imported
    out = json.loads((tmp_path / "out.ipynb").read_text())
    assert "".join(out["cells"][-1]["outputs"][0]["text"]).strip() == "5"
