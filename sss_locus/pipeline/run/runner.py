"""Execute registered notebooks with papermill, hermetically, into their executed copies.

* The kernel is this environment's Python, kernel ``sss-locus`` of a kernelspec folder in the build
  area; ``IPYTHONDIR``, ``JUPYTER_*_DIR`` and ``MPLCONFIGDIR`` point there too, so a kernelspec in
  the home folder cannot shadow it and runs leave the user's Jupyter/Matplotlib state alone.
* The kernel's working directory is the executed copy's folder (papermill ``--cwd``).
* The cell papermill injects with the run's parameters is a small collapsed block in the book.
* Runs are atomic: papermill runs in a child process (its own session) into a private staging
  folder (``<build>/tmp/run-...``; a side run's beside its ``--output``) with the kernel's
  connection file in that folder too. Only a run that succeeds replaces the executed copy and
  its figures (:func:`sss_locus.pipeline.run.outputs.commit_run`, under the build area's lock). A run
  that fails or is interrupted (exception, Ctrl-C, SIGTERM, SIGHUP) ends its papermill child, the
  kernel and the kernel's own processes (:func:`.orphans.stop_process_tree`), then deletes the staging folder and leaves the last good results
  untouched; a failed run's notebook is kept as ``<build>/failed/<name>.ipynb`` for reading
  (outside the book source, so it cannot pass as a result).
* Side runs (``output=``) write the executed copy there and its figures into ``figures/`` beside
  it; they never touch the build area's results.
* The executed copy records a *run key* (hash of the notebook source, its parameters and
  profile, the package code and ``data/``, and ``environment.lock``, or an installed package's
  installed distributions, :func:`~sss_locus.pipeline.publish.provenance.environment_sha256`): :func:`is_up_to_date` tells
  ``sss-locus book`` that rerunning would reproduce the same result, so it can be skipped.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time
import uuid
from collections.abc import Iterator, Sequence
from concurrent.futures import ThreadPoolExecutor, as_completed
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from sss_locus import paths
from sss_locus.pipeline.run import atomic, budgets, context, faults, kernels, orphans, outputs, paramcell, preflight, progress, userfiles
from sss_locus.pipeline.publish import export, provenance
from sss_locus.pipeline.book import paperinputs, studies
from sss_locus.pipeline.run.kernels import KERNEL_NAME, hermetic_env, install_kernelspec
from sss_locus.pipeline.run.outputs import run_key
from sss_locus.pipeline.run.registry import NotebookEntry

def kernel_environment(staging: Path) -> dict[str, str]:
    """The environment of a run's papermill process and kernel: this one's without any
    ``SSS_LOCUS_*`` variable, the hermetic folders (:func:`.kernels.hermetic_env`), the connection
    file in the staging folder, and :data:`.context.RUN_ENV` naming the run's context file there."""
    env = {k: v for k, v in os.environ.items() if not k.startswith("SSS_LOCUS_")}
    env.update(hermetic_env())
    env.update({
        "JUPYTER_RUNTIME_DIR": str(staging / "runtime"),  # connection file goes with the staging folder
        "TMPDIR": str(staging / "runtime"),  # jupyter_client writes it with tempfile.mkstemp
        context.RUN_ENV: str(staging / context.FILE_NAME),
    })
    return env


def resolve_parameters(entry: NotebookEntry, profile: str, overrides: dict[str, Any] | None = None,
                       *, from_text: bool = False, data: Any = None) -> dict[str, Any]:
    """The run's parameters: :meth:`NotebookEntry.resolve`, then the user data inputs
    (``data``, a :class:`sss_locus.experiments.datamodel.userdata.DataInputs` from ``--data``/``--set``)
    as the ``data_files``/``data_set`` parameters of a notebook that declares them."""
    parameters = entry.resolve(profile, overrides, from_text=from_text)
    budgets.check_parameters(parameters)  # memory and time the parameters alone would take
    parameters.update(userfiles.file_parameters(parameters))  # a user's observations or area file, read
    if data is not None and not data.is_default:
        for name, value in (("data_files", list(data.files)), ("data_set", list(data.sets))):
            if name in parameters and value:
                parameters[name] = value
    return parameters


def is_up_to_date(entry: NotebookEntry, profile: str, overrides: dict[str, Any] | None = None,
                  data: Any = None) -> bool:
    """True when the executed copy came from an identical, successful run (same parameters,
    ``--data`` files' bytes and overrides) and its figures are the ones that run exported, intact."""
    try:
        meta = json.loads(entry.executed_path().read_text(encoding="utf-8"))["metadata"]
        ours = meta.get("sss_locus", {})
        wanted = resolve_parameters(entry, profile, overrides, from_text=True, data=data)
        if ours.get("run_key") != run_key(entry, profile, wanted):
            return False
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return False
    return not outputs.problems([entry])


class NotebookFailed(RuntimeError):
    """A cell of a notebook raised, or the run was cut short; the last good results are kept.

    ``str()`` is one line (the failing cell and the error's last line, and where the failed
    notebook was kept); ``traceback`` holds the full traceback.
    """

    def __init__(self, summary: str, traceback: str = "", kept: Path | None = None) -> None:
        where = f"; the failed notebook is kept in {kept}" if kept else ""
        super().__init__(summary + where)
        self.traceback = traceback
        self.kept = kept


def _label_injected_cell(executed: Path, profile: str, parameters: dict[str, Any], extra: dict[str, Any]) -> None:
    """Show the run's values in the visible parameters cell (:mod:`.paramcell`) and tag papermill's
    injected-parameters cell, which also names the data files read, so the book shows it collapsed."""
    nb = json.loads(executed.read_text(encoding="utf-8"))
    paramcell.show_run_values(nb["cells"], paths.public_values(parameters),
                              f"# The values this run used (profile '{profile}'); "
                              "defaults and ranges: `sss-locus params NOTEBOOK`\n")
    for cell in nb["cells"]:
        tags = cell.get("metadata", {}).get("tags", [])
        if "injected-parameters" in tags:
            cell["metadata"]["tags"] = sorted(set(tags) | {"hide-input"})
            cell["metadata"]["mystnb"] = {
                "code_prompt_show": "Show the data files this run read and papermill's record of its parameters",
                "code_prompt_hide": "Hide the data files and papermill's record",
            }
            source = "".join(cell["source"]) if isinstance(cell["source"], list) else cell["source"]
            header = f"# Parameters of this run (profile '{profile}'), injected by papermill\n"
            if "data" in extra:
                header += "".join(f"# data file read: {paths.public_path(f['path'])} ({f['role']}, sha256 "
                                  f"{f['sha256']})\n" for f in extra["data"]["files"])
                for f in extra["data"]["files"]:  # the page names a user's file, not where it sits
                    source = source.replace(json.dumps(f["path"])[1:-1], paths.public_path(f["path"]))
                header += "".join(f"# data override: {o}\n" for o in extra["data"]["overrides"])
            header += "".join(f"# warning: {w}\n" for w in extra.get("warnings", []))  # a user's file read in part
            for value in parameters.values():  # a user's area, sightings or truth file, by its name
                if isinstance(value, str) and os.path.isabs(value):
                    source = source.replace(json.dumps(value)[1:-1], paths.public_path(value))
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


_CHILD = kernels.PAPERMILL_CHILD  # a name of its own: the tests replace it


#: Errors of a kernel that never started (no cell ran): jupyter_client picks free ports and
#: releases them before the kernel binds them, so kernels started at the same moment can collide
#: (papermill issue #511). Such a run is retried; a failure inside a cell never is.
KERNEL_START_ERRORS = ("Kernel died before replying to kernel_info", "Kernel didn't respond in")
KERNEL_START_ATTEMPTS = 3


def _execute(entry: NotebookEntry, staging: Path, notebook: Path, cwd: Path,
             parameters: dict[str, Any]) -> None:
    """Run papermill in a child process (own session) into ``notebook``; kill it if we stop.
    A kernel that dies before running any cell is started again, at most
    :data:`KERNEL_START_ATTEMPTS` times in all."""
    args = staging / "papermill-args.json"
    args.write_text(json.dumps({
        "input_path": str(entry.source), "output_path": str(notebook), "parameters": parameters,
        "kernel_name": KERNEL_NAME, "cwd": str(cwd), "progress_bar": False, "log_output": False,
    }, default=provenance.json_default), encoding="utf-8")
    log_file = staging / "papermill.log"
    for _attempt in range(KERNEL_START_ATTEMPTS):
        code = _papermill_child(args, log_file)
        log = log_file.read_text(encoding="utf-8", errors="replace")
        if code == 0 or not any(e in log for e in KERNEL_START_ERRORS) or _cells_ran(notebook):
            break
    if code != 0:
        nb = outputs.read_notebook(notebook) if notebook.is_file() else None
        error = outputs.notebook_error(nb) if nb else None
        if error:
            raise NotebookFailed(f"notebook {entry.name!r} failed in {error[0]}", error[1])
        raise NotebookFailed(f"notebook {entry.name!r} did not run: {faults.papermill_failure(log, staging.parent)}", log)


def _papermill_child(args: Path, log_file: Path) -> int:
    """One papermill process for ``args``, its output in ``log_file``; its exit code."""
    with open(log_file, "wb") as log_fh:
        child = subprocess.Popen([sys.executable, "-c", _CHILD, str(args)], stdout=log_fh,
                                 env=kernel_environment(args.parent),
                                 stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, start_new_session=True,
                                 preexec_fn=orphans.die_with_parent)  # even if we are SIGKILLed
        try:
            return child.wait()
        finally:
            if child.poll() is None:  # we were interrupted: stop papermill, its kernel and theirs
                with outputs.signals_held():  # a second Ctrl-C must not leave them suspended
                    orphans.stop_process_tree(child.pid)
                    child.wait()


def _cells_ran(notebook: Path) -> bool:
    """Whether papermill's output ``notebook`` shows an executed code cell (belt and braces: the
    kernel-start errors occur before the first cell)."""
    nb = outputs.read_notebook(notebook) if notebook.is_file() else None
    return bool(nb) and any(c.get("cell_type") == "code" and c.get("execution_count")
                            for c in nb.get("cells", []))


def run_notebook(entry: NotebookEntry, profile: str = "book", overrides: dict[str, Any] | None = None,
                 *, from_text: bool = False, output: Path | None = None, log=print, data: Any = None) -> Path:
    """Execute one registered notebook, atomically, into its executed copy; return that path.

    Parameters are the notebook defaults, then the profile's values, then ``overrides`` (command
    line text when ``from_text``); all are validated (the notebook's ``Params`` model) before
    anything runs. Raises :class:`sss_locus.pipeline.run.registry.ParameterError` for bad parameters
    and :class:`NotebookFailed` when a cell fails; the executed copy and figures of the last good
    run are then untouched. ``output`` makes a side run: the executed copy goes there and its
    figures into ``figures/`` beside it, and the build area's results are not touched. ``data``
    (:class:`sss_locus.experiments.datamodel.userdata.DataInputs`, validated by the caller) becomes the
    notebook's ``data_files``/``data_set`` parameters.
    """
    parameters = resolve_parameters(entry, profile, overrides, from_text=from_text, data=data)
    warnings = userfiles.file_warnings(parameters)  # a user's file read in part: said now and recorded
    for line in warnings:
        print(f"sss-locus: warning: {line}", file=sys.stderr)
    side = output is not None
    executed = preflight.check_side_output(output, entry) if side else entry.executed_path()
    figures = executed.parent / paths.FIGURES_SUBDIR if side else paths.figures_dir()
    if not side:
        preflight.check_writable(paths.build_dir(), "build area")
        for folder, what in ((executed.parent, "executed-copies folder"), (figures, "figures folder")):
            preflight.check_writable(folder, what)  # a read-only one found now, not at the commit
    executed.parent.mkdir(parents=True, exist_ok=True)
    tmp_root = executed.parent if side else paths.build_dir() / "tmp"
    tmp_root.mkdir(parents=True, exist_ok=True)
    orphans.remove_stale_staging(tmp_root)  # left by runs that were killed (SIGKILL)
    orphans.remove_stale_temporaries(figures, executed.parent)  # ... during their commit
    staging = tmp_root / f".run-{entry.name}-{os.getpid()}-{uuid.uuid4().hex[:12]}"
    key = run_key(entry, profile, parameters)
    run = context.current().replace(  # what the kernel knows of its run: one file, one variable
        notebook=entry.source_relative, profile=profile, parameters=parameters, run_key=key,
        figures_dir=staging / "figures", progress_file=staging / "progress.txt",
        data_reads_file=staging / "data-reads.txt")  # the data entries the kernel's loaders read
    staged = staging / executed.name
    start = time.perf_counter()
    log(progress.start_line(entry.name, profile))
    try:
        with atomic.signals_as_exceptions():
            (staging / "runtime").mkdir(parents=True)
            context.write(run, staging)
            install_kernelspec()
            try:
                with progress.relay_batches(staging / "progress.txt", entry.name, log):
                    _execute(entry, staging, staged, executed.parent, parameters)
            except NotebookFailed as exc:
                kept = executed.with_name(executed.stem + ".failed.ipynb") if side else \
                    paths.build_dir() / "failed" / executed.name
                if staged.is_file() and faults.keep_failed_notebook(staged, kept):
                    exc.kept = kept
                    exc.args = (f"{exc.args[0]}; the failed notebook is kept in {kept}",)
                raise
            exported = sorted(m["label"] for m in export.load_manifests(staging / "figures", export.KINDS))
            record = {"run_key": key, "figures": exported, **({"warnings": warnings} if warnings else {})}
            if "data_files" in parameters:
                from sss_locus.experiments.datamodel import userdata

                inputs = userdata.make_inputs(parameters["data_files"], parameters.get("data_set", []))
                record["data"] = {"files": userdata.files_read(inputs), "overrides": list(inputs.sets)}
                reads = staging / "data-reads.txt"
                record["data_read"] = userdata.datadoc.entries_sha256(
                    reads.read_text(encoding="utf-8").split() if reads.is_file() else [], inputs)
            record["paper_inputs"] = paperinputs.compare(entry, parameters, list(record.get("data_read", ())))
            _label_injected_cell(staged, profile, parameters, record)
            studies.drop_skipped(staged)  # a study no platform of the run can fly: a note, not its cells
            with outputs.build_lock() if not side else _nothing():
                removed = [] if side else sorted(set(outputs.labels_of(figures, entry.source_relative)) - set(exported))
                outputs.commit_run(staged, staging / "figures", executed, figures,
                                   None if side else entry.source_relative)
    finally:
        with outputs.signals_held():  # removed whole, even if a second signal comes
            shutil.rmtree(staging, ignore_errors=True)
    log(f"ran {entry.name} [{profile}] in {time.perf_counter() - start:.1f} s -> {executed}")
    if exported:
        log(f"  figures and tables: {', '.join(exported)} -> {figures}")
    if removed:  # one executed copy per chapter and build area: its earlier figures go with it
        log(f"  removed (this chapter's previous run in this build area drew them, this one does not): "
            f"{', '.join(removed)}")
    return executed


def declared_overrides(entry: NotebookEntry, overrides: dict[str, str] | None) -> dict[str, str]:
    """The overrides whose parameter ``entry`` declares."""
    names = entry.parameters()
    return {k: v for k, v in (overrides or {}).items() if k in names}


@contextmanager
def _nothing() -> Iterator[None]:
    yield


@contextmanager
def _removed(folder: Path) -> Iterator[None]:
    """Delete ``folder`` when the block ends (a killed process's: :func:`.orphans.remove_stale_staging`)."""
    try:
        yield
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def run_many(entries: Sequence[NotebookEntry], profile: str, jobs: int = 1, log=print,
             verbose: bool = False, overrides: dict[str, str] | None = None, data: Any = None) -> None:
    """Run several registered notebooks with one profile, up to ``jobs`` at a time.

    With ``jobs > 1`` each notebook runs in its own ``sss-locus run`` process, which gets this
    process's run context (:mod:`.context`) in a file. Every notebook is attempted; failures are reported
    together at the end as a ``RuntimeError``. ``overrides`` (command-line text) apply to the
    notebooks that declare each parameter; ``data`` are the ``--data``/``--set`` inputs. If this process is interrupted, the running
    children get SIGTERM (each cleans up after itself) before the interruption propagates.
    """
    bar = progress.NotebookBar(len(entries))
    log = bar.write if log is print else log
    if jobs <= 1 or len(entries) <= 1:
        failures = []
        for entry in entries:
            try:
                with bar.timed(entry.name):
                    run_notebook(entry, profile, declared_overrides(entry, overrides), from_text=True, log=log, data=data)
            except NotebookFailed as exc:
                failures.append(f"{entry.name}: {exc}" + (f"\n{exc.traceback}" if verbose else ""))
        if failures:
            raise RuntimeError(f"{len(failures)} notebook(s) failed:\n" + "\n".join(failures))
        return
    install_kernelspec()
    children: dict[str, subprocess.Popen] = {}
    shared = paths.build_dir() / "tmp" / f"{orphans.STAGING_PREFIX}book-{os.getpid()}-{uuid.uuid4().hex[:12]}"
    child_env = context.child_environment(context.current().replace(quiet_batches=True), os.environ,
                                          shared / context.FILE_NAME)  # the children's run context

    def one(entry: NotebookEntry) -> tuple[int, str, str]:
        cmd = [sys.executable, "-m", "sss_locus.pipeline.cli.command", "run", entry.name, "--profile", profile,
               *(["--verbose"] if verbose else [])]
        for name, value in declared_overrides(entry, overrides).items():
            cmd += ["-p", name, value]
        if data is not None:
            cmd += [arg for f in data.files for arg in ("--data", f)]
            cmd += [arg for o in data.sets for arg in ("--set", o)]
        log(progress.start_line(entry.name, profile))  # the child's own start line comes too late
        child = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                 stdin=subprocess.DEVNULL, env=child_env,
                                 preexec_fn=orphans.die_with_parent)  # a SIGKILLed book takes its runs along
        children[entry.name] = child
        out, err = child.communicate()
        return child.returncode, out, err

    failures: list[str] = []
    futures: dict = {}
    with _removed(shared), atomic.signals_as_exceptions(), ThreadPoolExecutor(max_workers=jobs) as pool:
        try:
            futures = {pool.submit(one, entry): entry for entry in entries}
            for future in as_completed(futures):
                entry, (code, out, err) = futures[future], future.result()
                for line in out.splitlines():
                    if not line.startswith(("Rebuild the site", progress.START_PREFIX)):
                        log(line)
                bar.finished(entry.name, code == 0)
                if code != 0:
                    failures.append(f"{entry.name}: {err.strip()[-4000:]}")
        except BaseException:
            for future in futures:
                future.cancel()
            for child in children.values():
                if child.poll() is None:
                    child.terminate()
            raise
    if failures:
        raise RuntimeError(f"{len(failures)} notebook(s) failed:\n" + "\n".join(failures))
