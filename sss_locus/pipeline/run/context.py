"""The run context: everything a process of a run needs to know about it, in one frozen object.

A run has three kinds of processes: the ``sss-locus`` command, the ``sss-locus run`` children of
``sss-locus book --jobs N``, and each notebook's kernel. They share one :class:`RunContext`
(build area, cache folder, figures folder, run key, notebook, profile, parameters, budgets,
scheduler, the folder the command was started in ...). The runner writes it as JSON into the
run's staging folder and gives the kernel one environment variable, :data:`RUN_ENV`
(``SSS_LOCUS_RUN``), naming that file; the kernel reads it once. Nothing else passes between
runner and kernel through the environment.

:func:`current` is the context of this process:

1. the innermost :func:`use` block (the command line's ``--name``, ``--workers`` ...);
2. else the file named by ``SSS_LOCUS_RUN`` (a kernel, or a child ``sss-locus run``), read once;
3. else, the **default** — a notebook opened by hand in Jupyter, a script, a test — from the
   user's settings (:func:`from_environment`): ``SSS_LOCUS_BUILD_DIR`` (the build area,
   ``<repo>/_build`` by default; an installed package without a checkout: ``_build`` in the
   working directory), ``SSS_LOCUS_CACHE_DIR`` (``<repo>/.cache``, or ``.cache`` there),
   ``SSS_LOCUS_MEMORY_BUDGET`` (bytes; half the RAM), ``SSS_LOCUS_TIME_BUDGET_S`` (a day) and
   ``SSS_LOCUS_SCHEDULER`` (``local:N`` or a Dask address; unset: in-process); no run key,
   notebook ``"interactive"``, profile ``"none"``, no parameters, figures into ``figures/`` of
   the working directory, no progress file.

The lower layers do not import this module: :mod:`sss_locus.paths` (build area and cache),
:mod:`sss_locus.geometry.validation` (memory budget) and :mod:`sss_locus.experiments.stats.scale`
(scheduler) each read one setting through a function this module installs when it is imported
(so any process that runs the pipeline answers from its context).
"""

from __future__ import annotations

import dataclasses
import json
import os
from collections.abc import Iterator, Mapping
from contextlib import ExitStack, contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from sss_locus import paths
from sss_locus.experiments.stats import scale
from sss_locus.geometry import validation

#: The one environment variable between a run's processes: the path of its context file.
RUN_ENV = "SSS_LOCUS_RUN"
#: The user's settings read by :func:`from_environment` (not a channel between processes).
TIME_BUDGET_ENV = "SSS_LOCUS_TIME_BUDGET_S"
SETTINGS_ENV = (paths.BUILD_DIR_ENV, paths.CACHE_DIR_ENV, validation.MEMORY_BUDGET_ENV, TIME_BUDGET_ENV,
                scale.SCHEDULER_ENV)
#: The context file's name in a run's staging folder.
FILE_NAME = "run-context.json"


@dataclass(frozen=True)
class RunContext:
    """What a run is and where it writes (see the module docstring for the defaults).

    Attributes
    ----------
    build_dir : Path
        The build area (``<repo>/_build``, ``$SSS_LOCUS_BUILD_DIR``, or a named area inside it).
    build_name : str or None
        The named build area (``--name``), ``None`` in the reproduction's.
    cache_dir : Path
        The result cache.
    caller_dir : Path
        The folder the outermost command was started in (a relative path the user typed).
    notebook : str
        Repository-relative path of the notebook run, ``"interactive"`` outside a run.
    profile : str
        The run's parameter profile, ``"none"`` outside a run.
    parameters : Mapping
        The run's resolved parameters (``{}`` outside a run).
    run_key : str or None
        The run key its executed copy and figures record.
    figures_dir : Path or None
        Where the run's figures are exported (its staging folder); ``None``: ``figures/`` of the
        working directory.
    progress_file : Path or None
        Where the kernel's studies append their batches (:mod:`sss_locus.pipeline.run.progress`).
    data_reads_file : Path or None
        Where the kernel writes the data entries its loaders read (:func:`save_data_reads`).
    quiet_batches : bool
        No progress bars (a child run of ``book --jobs N``).
    reproduction_checked : bool
        The command has checked its runs against the paper's inputs (:mod:`~sss_locus.pipeline.book.areas`).
    scheduler : str
        ``local:N``, a Dask scheduler address, or ``""`` (in-process).
    memory_budget : str
        Bytes one request may plan to use, as set (``""``: half the RAM).
    time_budget_s : str
        Seconds a run may be estimated to take, as set (``""``: a day).
    """

    build_dir: Path
    cache_dir: Path
    caller_dir: Path
    build_name: str | None = None
    notebook: str = "interactive"
    profile: str = "none"
    parameters: Mapping[str, Any] = field(default_factory=dict)
    run_key: str | None = None
    figures_dir: Path | None = None
    progress_file: Path | None = None
    data_reads_file: Path | None = None
    quiet_batches: bool = False
    reproduction_checked: bool = False
    scheduler: str = ""
    memory_budget: str = ""
    time_budget_s: str = ""

    def replace(self, **changes: Any) -> RunContext:
        """A copy with ``changes``."""
        return dataclasses.replace(self, **changes)

    def to_json(self) -> str:
        """The context as JSON (paths as strings; parameters through :func:`.provenance.json_default`)."""
        from sss_locus.pipeline.publish.provenance import json_default

        values = {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}
        return json.dumps({k: str(v) if isinstance(v, Path) else v for k, v in values.items()},
                          sort_keys=True, indent=1, default=json_default)

    @classmethod
    def from_json(cls, text: str) -> RunContext:
        """The context :meth:`to_json` wrote."""
        values = json.loads(text)
        known = {f.name: f for f in dataclasses.fields(cls)}
        unknown = sorted(set(values) - set(known))
        if unknown:
            raise ValueError(f"run context has unknown fields {unknown}")
        for name in ("build_dir", "cache_dir", "caller_dir", "figures_dir", "progress_file", "data_reads_file"):
            if values.get(name) is not None:
                values[name] = Path(values[name])
        return cls(**values)


def from_environment(environ: Mapping[str, str] | None = None) -> RunContext:
    """The default context of a process outside any run: the user's settings (module docstring)."""
    env = os.environ if environ is None else environ
    build = env.get(paths.BUILD_DIR_ENV)
    cache = env.get(paths.CACHE_DIR_ENV)
    return RunContext(
        build_dir=Path(build).resolve() if build else paths.work_root() / "_build",
        cache_dir=Path(cache).resolve() if cache else paths.work_root() / ".cache",
        caller_dir=Path.cwd(),
        scheduler=env.get(scale.SCHEDULER_ENV, ""),
        memory_budget=env.get(validation.MEMORY_BUDGET_ENV, ""),
        time_budget_s=env.get(TIME_BUDGET_ENV, ""),
    )


_ACTIVE: list[RunContext] = []  # the use() blocks, innermost last (one list for every thread)
_LOADED: dict[str, RunContext] = {}  # the context file of this process, read once


def load(path: str | os.PathLike) -> RunContext:
    """The context in the file ``path`` (one-line ``ValueError`` if it cannot be read)."""
    try:
        return RunContext.from_json(Path(path).read_text(encoding="utf-8"))
    except (OSError, ValueError, TypeError) as exc:
        raise ValueError(f"{RUN_ENV}={path}: cannot read the run context ({exc})") from None


def current() -> RunContext:
    """The context of this process (see the module docstring for the order)."""
    if _ACTIVE:
        return _ACTIVE[-1]
    file = os.environ.get(RUN_ENV)
    if file:
        if file not in _LOADED:
            _LOADED[file] = load(file)
        return _LOADED[file]
    return from_environment()


@contextmanager
def use(context: RunContext) -> Iterator[RunContext]:
    """Within the block, :func:`current` is ``context`` (restored afterwards)."""
    depth = len(_ACTIVE)
    _ACTIVE.append(context)
    try:
        yield context
    finally:
        del _ACTIVE[depth:]


def amend(**changes: Any) -> None:
    """Change the context of the innermost :func:`use` block for the rest of it (a command that
    has checked something tells its later runs); nothing outside a block."""
    if _ACTIVE:
        _ACTIVE[-1] = _ACTIVE[-1].replace(**changes)


def write(context: RunContext, folder: Path) -> Path:
    """Write ``context`` as :data:`FILE_NAME` into ``folder``; its path."""
    folder.mkdir(parents=True, exist_ok=True)
    target = folder / FILE_NAME
    target.write_text(context.to_json() + "\n", encoding="utf-8")
    return target


def child_environment(context: RunContext, base: Mapping[str, str], file: Path) -> dict[str, str]:
    """``base`` without the user's settings (:data:`SETTINGS_ENV`: the context carries them) and
    with :data:`RUN_ENV` naming ``file``, where ``context`` is written: a child's environment."""
    file.parent.mkdir(parents=True, exist_ok=True)
    file.write_text(context.to_json() + "\n", encoding="utf-8")
    env = {k: v for k, v in base.items() if k not in SETTINGS_ENV}
    env[RUN_ENV] = str(file)
    return env


_KERNEL = ExitStack()  # a run's kernel: its recording of data entries read, open for the kernel's life
_KERNEL_READS: list[set[str]] = []  # ... and the entries it holds (enter_kernel)


def save_data_reads(*_: Any) -> None:
    """Write the data entries this kernel's loaders have read so far (recorded since
    :func:`enter_kernel`) to the context's ``data_reads_file``: called by the kernel after each
    cell, read by the runner when the notebook has run."""
    target = current().data_reads_file
    if target is None:
        return
    tmp = target.with_name(f".{target.name}.{os.getpid()}")
    reads = set().union(*_KERNEL_READS)
    tmp.write_text("".join(f"{e}\n" for e in sorted(reads)), encoding="utf-8")
    os.replace(tmp, target)


def enter_kernel(shell: Any) -> None:
    """Called by the run's kernel (:data:`sss_locus.pipeline.run.kernels.KERNEL_LAUNCHER`) before its
    first cell: read the context once, record the data entries the loaders read
    (:func:`sss_locus.experiments.datamodel.datadoc.recording`, open for the kernel's life) and write them
    after every cell (:func:`save_data_reads`)."""
    from sss_locus.experiments.datamodel import datadoc

    current()
    _KERNEL_READS.append(_KERNEL.enter_context(datadoc.recording()))
    shell.events.register("post_run_cell", save_data_reads)


def _areas() -> tuple[Path, str | None, Path]:
    ctx = current()
    return ctx.build_dir, ctx.build_name, ctx.cache_dir


# The lower layers' settings, answered from the context of this process.
paths.areas_setting = _areas
validation.memory_budget_setting = lambda: current().memory_budget  # noqa: E731
scale.scheduler_setting = lambda: current().scheduler  # noqa: E731
