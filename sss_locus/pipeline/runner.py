"""Execute registered notebooks with papermill, hermetically, into their executed copies.

* The kernel is this environment's Python, registered as kernel ``sss-locus`` in a
  kernelspec folder inside the build area (a kernelspec in the home folder cannot shadow it).
* ``IPYTHONDIR``, ``JUPYTER_DATA_DIR``, ``JUPYTER_RUNTIME_DIR`` and ``MPLCONFIGDIR`` point into
  the build area, so runs neither read nor write the user's Jupyter/Matplotlib state.
* The kernel's working directory is the executed copy's folder (papermill ``--cwd``).
* The cell papermill injects with the run's parameters is tagged ``hide-input`` and labelled,
  so the book shows it as a small collapsed block.
* Figures a notebook exported earlier are removed first; the run re-exports them.
* The executed copy records a *run key* (hash of the notebook source, its parameters and
  profile, the package code and ``data/``, and ``environment.lock``): :func:`is_up_to_date` tells
  ``sss-locus book`` that rerunning would reproduce the same result, so it can be skipped.
"""

from __future__ import annotations

import hashlib
import json
import os
import subprocess
import sys
import time
from collections.abc import Iterator, Sequence
from concurrent.futures import ThreadPoolExecutor, as_completed
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from sss_locus import paths
from sss_locus.pipeline import export, provenance
from sss_locus.pipeline.registry import NotebookEntry

KERNEL_NAME = "sss-locus"


def hermetic_env() -> dict[str, str]:
    """Environment variables that keep kernels' state inside the build area."""
    root = paths.jupyter_dir()
    env = {
        "IPYTHONDIR": str(root / "ipython"),
        "JUPYTER_DATA_DIR": str(root / "data"),
        "JUPYTER_RUNTIME_DIR": str(root / "runtime"),
        "JUPYTER_CONFIG_DIR": str(root / "config"),
        "MPLCONFIGDIR": str(root / "matplotlib"),
        "MPLBACKEND": "Agg",
        "JUPYTER_PLATFORM_DIRS": "1",
        "PYDEVD_DISABLE_FILE_VALIDATION": "1",
        # Children (kernels, jupyter-book) must see the same build area and cache.
        paths.BUILD_DIR_ENV: str(paths.build_dir()),
        paths.CACHE_DIR_ENV: str(paths.cache_dir()),
    }
    for key in ("IPYTHONDIR", "JUPYTER_DATA_DIR", "JUPYTER_RUNTIME_DIR", "JUPYTER_CONFIG_DIR", "MPLCONFIGDIR"):
        Path(env[key]).mkdir(parents=True, exist_ok=True)
    return env


def install_kernelspec() -> Path:
    """Write the kernelspec of this Python as ``sss-locus`` under ``$JUPYTER_DATA_DIR/kernels``."""
    folder = paths.jupyter_dir() / "data" / "kernels" / KERNEL_NAME
    folder.mkdir(parents=True, exist_ok=True)
    spec = {
        "argv": [sys.executable, "-m", "ipykernel_launcher", "-f", "{connection_file}"],
        "display_name": "Python 3 (sss-locus)",
        "language": "python",
        "metadata": {"debugger": False},
    }
    tmp = folder / f".kernel.json.{os.getpid()}"
    tmp.write_text(json.dumps(spec, indent=1) + "\n", encoding="utf-8")
    os.replace(tmp, folder / "kernel.json")  # atomic: parallel runs may install at once
    return folder


@contextmanager
def patched_environ(values: dict[str, str]) -> Iterator[None]:
    """Temporarily set environment variables (kernels inherit them)."""
    saved = {key: os.environ.get(key) for key in values}
    os.environ.update(values)
    try:
        yield
    finally:
        for key, old in saved.items():
            if old is None:
                os.environ.pop(key, None)
            else:
                os.environ[key] = old


def run_key(entry: NotebookEntry, profile: str, parameters: dict[str, Any]) -> str:
    """Hash of everything an executed copy depends on (see the module docstring)."""
    payload = json.dumps(
        {"source": provenance.file_sha256(entry.source), "profile": profile, "parameters": parameters,
         "code": provenance.code_sha256(), "lock": provenance.lock_sha256()},
        sort_keys=True, default=provenance.json_default,
    )
    return hashlib.sha256(payload.encode()).hexdigest()


def is_up_to_date(entry: NotebookEntry, profile: str) -> bool:
    """True when the executed copy came from an identical run and its figures are intact."""
    executed = entry.executed_path()
    try:
        meta = json.loads(executed.read_text(encoding="utf-8"))["metadata"]
    except (OSError, ValueError, KeyError):
        return False
    ours = meta.get("sss_locus", {})
    if meta.get("papermill", {}).get("exception") or ours.get("run_key") != run_key(
        entry, profile, entry.resolve(profile)
    ):
        return False
    intact = {m["label"] for m in export.load_manifests() if m["notebook"] == entry.source_relative}
    return set(ours.get("figures", [])) <= intact


def _label_injected_cell(executed: Path, profile: str, parameters: dict[str, Any],
                         extra: dict[str, Any]) -> None:
    """Tag papermill's injected-parameters cell so the book shows it as a collapsed block."""
    nb = json.loads(executed.read_text(encoding="utf-8"))
    for cell in nb["cells"]:
        tags = cell.get("metadata", {}).get("tags", [])
        if "injected-parameters" in tags:
            cell["metadata"]["tags"] = sorted(set(tags) | {"hide-input"})
            cell["metadata"]["mystnb"] = {
                "code_prompt_show": f"Show this run's parameters (profile '{profile}')",
                "code_prompt_hide": "Hide this run's parameters",
            }
            source = "".join(cell["source"]) if isinstance(cell["source"], list) else cell["source"]
            header = f"# Parameters of this run (profile '{profile}'), injected by papermill\n"
            if not source.startswith(header):
                cell["source"] = header + source
    nb.setdefault("metadata", {})["sss_locus"] = {
        "profile": profile,
        "parameters": parameters,
        "git_commit": provenance.git_commit(),
        "package_version": provenance.package_version(),
        "lock_sha256": provenance.lock_sha256(),
        **extra,
    }
    executed.write_text(json.dumps(nb, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")


def run_notebook(entry: NotebookEntry, profile: str = "book", overrides: dict[str, Any] | None = None,
                 *, from_text: bool = False, output: Path | None = None, log=print) -> Path:
    """Execute one registered notebook into its executed copy; return that path.

    Parameters are the notebook defaults, then the profile's values, then ``overrides`` (command
    line text when ``from_text``); all are validated before anything runs. Raises
    :class:`sss_locus.pipeline.registry.ParameterError` for bad parameters and
    ``papermill.PapermillExecutionError`` when a cell fails (the executed copy then holds the
    traceback).
    """
    import papermill

    parameters = entry.resolve(profile, overrides, from_text=from_text)
    executed = entry.executed_path() if output is None else Path(output)
    executed.parent.mkdir(parents=True, exist_ok=True)
    env = hermetic_env()
    env[provenance.NOTEBOOK_ENV] = entry.source_relative
    env[provenance.PROFILE_ENV] = profile
    env[provenance.PARAMETERS_ENV] = json.dumps(parameters, sort_keys=True, default=provenance.json_default)
    with patched_environ(env):
        install_kernelspec()
        removed = export.remove_figures_of(entry.source_relative)
        start = time.perf_counter()
        papermill.execute_notebook(
            str(entry.source), str(executed), parameters=parameters, kernel_name=KERNEL_NAME,
            cwd=str(executed.parent), progress_bar=False, log_output=False,
        )
    exported = [m["label"] for m in export.load_manifests() if m["notebook"] == entry.source_relative]
    _label_injected_cell(executed, profile, parameters,
                         {"run_key": run_key(entry, profile, parameters), "figures": exported})
    log(f"ran {entry.name} [{profile}] in {time.perf_counter() - start:.1f} s -> {executed}")
    gone = sorted(set(removed) - set(exported))
    if exported:
        log(f"  figures: {', '.join(exported)}")
    if gone:
        log(f"  no longer exported: {', '.join(gone)}")
    return executed


def run_many(entries: Sequence[NotebookEntry], profile: str, jobs: int = 1, log=print) -> None:
    """Run several registered notebooks with one profile, up to ``jobs`` at a time.

    With ``jobs > 1`` each notebook runs in its own ``sss-locus run`` process (the environment
    variables a run sets are per process). Every notebook is attempted; failures are reported
    together at the end as a ``RuntimeError``.
    """
    if jobs <= 1 or len(entries) <= 1:
        for entry in entries:
            run_notebook(entry, profile, log=log)
        return
    install_kernelspec()

    def one(entry: NotebookEntry) -> subprocess.CompletedProcess:
        cmd = [sys.executable, "-m", "sss_locus.pipeline.cli", "run", entry.name, "--profile", profile]
        return subprocess.run(cmd, capture_output=True, text=True, stdin=subprocess.DEVNULL)

    failures = []
    with ThreadPoolExecutor(max_workers=jobs) as pool:
        futures = {pool.submit(one, entry): entry for entry in entries}
        for future in as_completed(futures):
            entry, result = futures[future], future.result()
            for line in result.stdout.splitlines():
                if not line.startswith("Rebuild the site"):
                    log(line)
            if result.returncode != 0:
                failures.append(f"{entry.name}: {result.stderr.strip()[-4000:]}")
    if failures:
        raise RuntimeError(f"{len(failures)} notebook(s) failed:\n" + "\n".join(failures))
