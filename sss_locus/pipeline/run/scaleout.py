"""``--scheduler`` / ``--workers`` of ``sss-locus run`` and ``sss-locus book``.

The notebooks' Monte Carlo studies read the run context's scheduler
(:mod:`sss_locus.pipeline.run.context`, passed to the kernels in their context file). ``--workers N`` starts one local cluster of
``N`` worker processes here (at most the cores this process may use; :func:`sss_locus.experiments.stats.scale.start_local_cluster`, the
launcher ``local:N`` uses too), shared by every notebook of the run; ``--scheduler ADDRESS``
uses a running Dask scheduler. Neither given: the studies run in the kernel, without Dask.
"""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Iterator
from contextlib import contextmanager

from sss_locus.experiments.stats.scale import start_local_cluster
from sss_locus.pipeline.run import context


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the two mutually exclusive options to a sub-command."""
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--scheduler", metavar="ADDRESS",
                       help="run the Monte Carlo chunks on this Dask scheduler (e.g. tcp://host:8786)")
    group.add_argument("--workers", type=int, metavar="N",
                       help="run the Monte Carlo chunks on a local Dask cluster of N processes")


def available_cores() -> int:
    """The cores this process may run on (its CPU affinity; the machine's count elsewhere)."""
    try:
        return len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        return os.cpu_count() or 1


@contextmanager
def scheduler_environment(args: argparse.Namespace) -> Iterator[None]:
    """The run context's scheduler for the duration of a command (and start a local cluster)."""
    if args.workers is not None and args.workers < 1:
        raise ValueError(f"--workers must be a positive integer; got {args.workers}")
    if args.workers is not None and args.workers > available_cores():
        print(f"sss-locus: --workers {args.workers} capped at {available_cores()}, the cores this process "
              "may use (more worker processes than cores only compete; --scheduler ADDRESS uses a cluster)",
              file=sys.stderr)
        args.workers = available_cores()
    if args.scheduler is None and args.workers is None:
        yield
        return
    cluster = None
    try:
        if args.workers is not None:
            cluster = start_local_cluster(args.workers)
            address = cluster.scheduler_address
        else:
            address = args.scheduler
        with context.use(context.current().replace(scheduler=address)):
            yield
    finally:
        if cluster is not None:
            cluster.close()
