"""Where the Monte Carlo studies run: in this process (default) or on a Dask cluster.

Each study is split into fixed chunks whose random draws come from their own
``numpy.random.SeedSequence`` children (the samplers' independently seeded blocks:
:mod:`sss_locus.experiments.pose_space.study`, :mod:`sss_locus.experiments.survey_passes.study`), and the
chunks' results are combined in chunk order. Where a chunk runs therefore does not change a
single number: the result is bit-identical serial, with one worker or with many.

The choice is the scheduler setting (:data:`scheduler_setting`): the environment variable
:data:`SCHEDULER_ENV` of a script, the run context's scheduler in a run (``sss-locus run`` and
``sss-locus book`` set it from ``--scheduler ADDRESS`` / ``--workers N``):

* unset or empty: every chunk runs here, in order; Dask is not imported;
* ``local:N``: a local cluster of ``N`` single-threaded worker processes, started on first use
  and kept for the rest of the process;
* anything else: the address of a running Dask distributed scheduler (``tcp://host:8786``).

Dask (``dask[distributed]``) is the optional extra ``scale`` of the package.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from typing import Any

SCHEDULER_ENV = "SSS_LOCUS_SCHEDULER"


def _environment_scheduler() -> str:
    """The scheduler setting of a script: the environment variable :data:`SCHEDULER_ENV`.

    Returns
    -------
    str
        ``local:N``, a scheduler address, or ``""`` (in-process).
    """
    return os.environ.get(SCHEDULER_ENV, "")


#: ``() -> str``: the scheduler setting. A script's is ``$SSS_LOCUS_SCHEDULER``; a process of the
#: pipeline answers from its run context (:mod:`sss_locus.pipeline.run.context` installs itself).
scheduler_setting: Callable[[], str] = _environment_scheduler
"""Environment variable naming the Dask scheduler (see the module docstring)."""

_CLIENTS: dict[str, Any] = {}


def parse_scheduler(value: str | None) -> tuple[str, int | str] | None:
    """``None`` (in-process), ``("local", n_workers)`` or ``("address", address)``.

    Raises ``ValueError`` naming :data:`SCHEDULER_ENV` for ``local:N`` with ``N`` not a
    positive integer.

    Parameters
    ----------
    value : str or None
        The setting: empty or ``None``, ``local:N`` or a scheduler address.

    Returns
    -------
    tuple or None
        As above.
    """
    text = (value or "").strip()
    if not text:
        return None
    if text.startswith("local:"):
        count = text.split(":", 1)[1]
        if not count.isdigit() or int(count) < 1:
            raise ValueError(f"{SCHEDULER_ENV}=local:N needs N a positive integer (worker "
                             f"processes); got {text!r}")
        return ("local", int(count))
    return ("address", text)


#: Bytes of freed memory a local worker keeps before returning it to the OS (glibc's
#: ``MALLOC_TRIM_THRESHOLD_``; Dask's default for workers is 65536).
LOCAL_MALLOC_TRIM_THRESHOLD = 256 * 2**20
_TRIM = "MALLOC_TRIM_THRESHOLD_"


def start_local_cluster(n_workers: int):
    """A Dask ``LocalCluster`` of ``n_workers`` single-threaded worker processes.

    The one launcher of both ``local:N`` (:func:`client`) and ``sss-locus run/book --workers N``
    (:mod:`sss_locus.pipeline.run.scaleout`). Its workers start with
    ``MALLOC_TRIM_THRESHOLD_`` = :data:`LOCAL_MALLOC_TRIM_THRESHOLD`, set through Dask's
    configuration ``distributed.nanny.pre-spawn-environ``: with Dask's default (65536) glibc
    hands every large array back to the OS and the next chunk page-faults it in again, which
    raised the kernel's CPU time per chunk by ~70 % (benchmarks/bench_studies.py). By Dask's
    rule a ``MALLOC_TRIM_THRESHOLD_`` already in this process's environment takes precedence
    (a user who sets it gets that value). Dask's nannies copy their spawn variables into this
    process's environment (``OMP_NUM_THREADS=1`` among them); the environment is restored
    after the start, so the variables reach only the workers, not this process, a later
    cluster or a notebook kernel started from here.

    Raises ``RuntimeError`` naming the extra to install if Dask is missing.

    Parameters
    ----------
    n_workers : int
        Worker processes, ``>= 1``.

    Returns
    -------
    distributed.LocalCluster
        The running cluster.
    """
    try:
        import dask
        from dask.distributed import LocalCluster
    except ImportError as exc:  # pragma: no cover - depends on the installed extras
        raise RuntimeError("a local Dask cluster needs the extra `sss-locus[scale]` "
                           "(dask[distributed])") from exc
    before = dict(os.environ)
    try:
        with dask.config.set({f"distributed.nanny.pre-spawn-environ.{_TRIM}":
                              str(LOCAL_MALLOC_TRIM_THRESHOLD)}):
            # ":0": the scheduler's HTTP server (started even without a dashboard) on a free
            # port, not on 8787, which a second cluster (or a test's) would find taken and warn
            return LocalCluster(n_workers=n_workers, threads_per_worker=1, processes=True,
                                dashboard_address=":0")
    finally:
        for key in set(os.environ) - set(before):
            del os.environ[key]
        os.environ.update({k: v for k, v in before.items() if os.environ.get(k) != v})


def client(value: str):
    """The Dask client for a scheduler setting (created once per process and setting).

    Parameters
    ----------
    value : str
        A scheduler setting (:func:`parse_scheduler`).

    Returns
    -------
    distributed.Client
        The client.
    """
    kind, arg = parse_scheduler(value)
    if value not in _CLIENTS:
        try:
            from dask.distributed import Client
        except ImportError as exc:  # pragma: no cover - depends on the installed extras
            raise RuntimeError(f"{SCHEDULER_ENV}={value!r} needs Dask: install the extra "
                               "`sss-locus[scale]` (dask[distributed])") from exc
        _CLIENTS[value] = Client(start_local_cluster(arg) if kind == "local" else arg)
    return _CLIENTS[value]


def close_clients() -> None:
    """Close every client (and local cluster) this process opened."""
    while _CLIENTS:
        dask_client = _CLIENTS.popitem()[1]
        cluster = getattr(dask_client, "cluster", None)
        dask_client.close()
        if cluster is not None:
            cluster.close()


def map_chunks(fn: Callable, tasks: Sequence[tuple], progress: Callable[[int, int], Any] | None = None) -> list:
    """``[fn(*task) for task in tasks]``, in order, here or on the configured Dask cluster.

    ``fn`` must be a module-level function and each task's arguments picklable; each chunk is
    a pure function of its arguments (its own seed), so the result does not depend on where it
    ran. ``progress``, if given, is called as ``progress(done, total)`` once after each chunk
    finishes (on a cluster, in the order the futures complete; the results keep task order); it
    only observes, so the result is the same with or without it. This layer never prints.

    Parameters
    ----------
    fn : callable
        Module-level function.
    tasks : sequence of tuple
        Arguments of each call.
    progress : callable, optional
        ``progress(done, total)``.

    Returns
    -------
    list
        The results, in task order.
    """
    setting = scheduler_setting()
    if parse_scheduler(setting) is None or len(tasks) < 2:
        results = []
        for task in tasks:
            results.append(fn(*task))
            if progress is not None:
                progress(len(results), len(tasks))
        return results
    dask_client = client(setting)
    futures = dask_client.map(fn, *zip(*tasks), pure=False)
    if progress is not None:
        from dask.distributed import as_completed

        for done, _ in enumerate(as_completed(futures), start=1):
            progress(done, len(tasks))
    return dask_client.gather(futures)


def _part(output, index: int):
    """Part ``index`` of a map task's output ``(summary, parts)``: ``summary`` for -1."""
    return output[0] if index < 0 else output[1][index]


def map_reduce(map_fn: Callable, tasks: Sequence[tuple], reduce_fn: Callable, n_parts: int,
               progress: Callable[[int, int], Any] | None = None) -> tuple[list, list]:
    """Reduce where the data lives: ``(summaries, reduced)`` of a two-stage computation.

    Each task runs ``map_fn(*task) -> (summary, parts)`` with ``parts`` a sequence of
    ``n_parts`` objects (e.g. the rows of one heatmap panel); then, for each ``g``,
    ``reduce_fn(g, [parts[g] of every task, in task order])``. Returns the summaries in task
    order and the reduced results in part order. In this process (no scheduler, or a single
    task) that is plain composition. On a Dask cluster the map outputs stay on the workers
    that made them; the parts move between workers to the reduce tasks, and only the
    summaries and the reduced results travel to this process. Both stages are pure functions of
    their arguments, combined in a fixed order, so the result is bit-identical here and on any
    number of workers. ``progress(done, total)`` is called after each map task.

    Parameters
    ----------
    map_fn : callable
        ``map_fn(*task) -> (summary, parts)``.
    tasks : sequence of tuple
        Arguments of each map call.
    reduce_fn : callable
        ``reduce_fn(g, parts_g)``.
    n_parts : int
        Parts per map output.
    progress : callable, optional
        ``progress(done, total)``.

    Returns
    -------
    summaries : list
        In task order.
    reduced : list
        In part order.
    """
    setting = scheduler_setting()
    if parse_scheduler(setting) is None or len(tasks) < 2:
        outputs = map_chunks(map_fn, tasks, progress)
        return ([out[0] for out in outputs],
                [reduce_fn(g, [out[1][g] for out in outputs]) for g in range(n_parts)])
    dask_client = client(setting)
    mapped = dask_client.map(map_fn, *zip(*tasks), pure=False)
    summaries = [dask_client.submit(_part, f, -1, pure=False) for f in mapped]
    reduced = [dask_client.submit(reduce_fn, g, [dask_client.submit(_part, f, g, pure=False) for f in mapped],
                                  pure=False) for g in range(n_parts)]
    if progress is not None:
        from dask.distributed import as_completed

        for done, _ in enumerate(as_completed(mapped), start=1):
            progress(done, len(tasks))
    result = dask_client.gather([summaries, reduced])
    del mapped, summaries, reduced  # releases the tables held on the workers
    return result[0], result[1]
