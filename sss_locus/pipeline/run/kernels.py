"""The kernel of a notebook run and the process that drives it: the hermetic environment both
start in, the kernelspec (``sss-locus``, this environment's Python) and the papermill command.

Both programs are written for a short run of one notebook: each kernel start waits for
papermill's imports, and papermill waits for the kernel's exit after the last cell.
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

from sss_locus import paths

KERNEL_NAME = "sss-locus"


#: Threads of the BLAS/OpenMP libraries in a notebook's kernel. One: OpenBLAS splits a matrix
#: product by its thread count, so the last bits of e.g. a Spearman rho (2.8e-17 measured) would
#: depend on the machine's cores and on how many notebooks run at once; and two notebooks run side
#: by side (``sss-locus book --jobs 2``) with two BLAS threads each made the bootstrap's matrix
#: products (when the intervals were bootstrapped) 10-20x slower on 2 cores. Dask's workers run with one thread too.
KERNEL_BLAS_THREADS = "1"


def hermetic_env() -> dict[str, str]:
    """Environment variables that keep kernels' state inside the build area and their numbers
    independent of the machine's core count (:data:`KERNEL_BLAS_THREADS`)."""
    root = paths.jupyter_dir()
    env = {
        **{var: KERNEL_BLAS_THREADS for var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")},
        "IPYTHONDIR": str(root / "ipython"),
        "JUPYTER_DATA_DIR": str(root / "data"),
        "JUPYTER_RUNTIME_DIR": str(root / "runtime"),
        "JUPYTER_CONFIG_DIR": str(root / "config"),
        "MPLCONFIGDIR": str(root / "matplotlib"),
        "MPLBACKEND": "Agg",
        "JUPYTER_PLATFORM_DIRS": "1",
        "PYDEVD_DISABLE_FILE_VALIDATION": "1",
    }
    for key in ("IPYTHONDIR", "JUPYTER_DATA_DIR", "JUPYTER_RUNTIME_DIR", "JUPYTER_CONFIG_DIR", "MPLCONFIGDIR"):
        Path(env[key]).mkdir(parents=True, exist_ok=True)
    return env


#: The kernel's program: ``python -m ipykernel_launcher`` (the working directory off ``sys.path``
#: while ipykernel loads; IPython puts it back), plus, as its last exit handler, ``gc.freeze``:
#: the interpreter's final garbage collections then skip the objects of a chapter's libraries
#: (pandas, SciPy, matplotlib), which took about 0.4 s of CPU at every kernel's exit, and papermill
#: waits for that exit. Every library's own exit handler still runs (registered later, run first);
#: what is skipped is the finalisation of objects in reference cycles still alive at exit, which
#: Python never promises (a run's files are written and closed by its cells). Before the first
#: cell, the kernel reads its run context (``SSS_LOCUS_RUN``) and, after every cell, records the
#: data entries its loaders have read (:func:`sss_locus.pipeline.run.context.enter_kernel`).
KERNEL_LAUNCHER = ("import atexit, gc, sys\n"
                   "if sys.path and sys.path[0] == '':\n    del sys.path[0]\n"
                   "atexit.register(gc.freeze)\n"
                   "from ipykernel import kernelapp\n"
                   "app = kernelapp.IPKernelApp.instance()\napp.initialize()\n"
                   "from sss_locus.pipeline.run import context\ncontext.enter_kernel(app.shell)\n"
                   "app.start()")


def install_kernelspec() -> Path:
    """Write the kernelspec of this Python as ``sss-locus`` under ``$JUPYTER_DATA_DIR/kernels``."""
    folder = paths.jupyter_dir() / "data" / "kernels" / KERNEL_NAME
    folder.mkdir(parents=True, exist_ok=True)
    spec = {
        "argv": [sys.executable, "-c", KERNEL_LAUNCHER, "-f", "{connection_file}"],
        "display_name": "Python 3 (sss-locus)",
        "language": "python",
        "metadata": {"debugger": False},
    }
    tmp = folder / f".kernel.json.{os.getpid()}"
    tmp.write_text(json.dumps(spec, indent=1) + "\n", encoding="utf-8")
    os.replace(tmp, folder / "kernel.json")  # atomic: parallel runs may install at once
    return folder


#: The papermill process. ``pyarrow.fs`` is marked absent: papermill imports it (and with it
#: pyarrow and numpy, half of papermill's import time) only to offer ``hdfs://`` paths, which a run
#: never uses; every kernel start waited for that import. Once papermill has returned (the kernel
#: shut down, the notebook written and closed), the process flushes its output and ends without
#: the interpreter's teardown (0.1-0.3 s of closing the messaging it no longer uses); a notebook
#: that fails raises before that, and the process exits with the traceback and status 1 as before.
PAPERMILL_CHILD = ("import json, os, sys\nsys.modules['pyarrow.fs'] = None\n"
                   "import papermill\npapermill.execute_notebook(**json.load(open(sys.argv[1])))\n"
                   "sys.stdout.flush()\nsys.stderr.flush()\nos._exit(0)")
