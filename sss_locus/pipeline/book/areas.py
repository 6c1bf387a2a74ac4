"""Named build areas: a run on other inputs than the paper's gets a book of its own, and the
reproduction stays as it is.

The model
---------
The build area ``_build/`` (:func:`sss_locus.paths.build_dir`) holds **the reproduction**: every
chapter run on the paper's inputs (each notebook's default ``platforms``, the shipped ``data/``),
its figures, their manifests and BibTeX, and the claims page built from them.

A run with ``--name NAME`` goes into its own build area ``_build/NAME/`` (executed copies,
figures, staging folders, lock) and ``sss-locus book --name NAME`` builds its own site into
``_build/NAME/html``. Every figure label there is the reproduction's label (``fig-heatmaps-auv``,
``fig-survey-passes``, ``fig-heatmaps-my-auv``), in its own namespace: a figure that combines the
user's platform with the paper's never overwrites the paper's figure of that label. The result
cache is shared, so the paper's platforms in a named run are cache hits.

A run *into the reproduction* whose inputs are not the paper's (``--data``, ``--set``, or a
``platforms`` list other than the notebook's default, a survey's ``observations`` file
other than the worked example's, or a survey ``area`` other than the example area) would replace paper figures and, without a
paper platform, the claims table. :func:`check_reproduction` refuses it before anything starts,
naming what it would replace, unless ``--replace-reproduction`` says to. Reruns of the paper's
platforms with other parameters (sample sizes, seeds, profiles; the "Rerunning a notebook" page)
stay allowed: they are reruns of the reproduction.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterable, Iterator, Mapping
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from sss_locus import paths
from sss_locus.pipeline.run import context

#: A build area's name: a folder of ``_build/`` (lower-case letters, digits, ``_`` and ``-``).
NAME_PATTERN = re.compile(r"[a-z0-9][a-z0-9_-]{0,63}")
#: Folders of a build area that a name must not shadow.
RESERVED = frozenset({"html", "source", "jupyter-book", "jupyter", "tmp", "failed", "singlehtml", "pdf",
                      "chromium-profile"})


def check_name(name: str) -> str:
    """``name`` if it is a valid build-area name, else ``ValueError`` naming the rule."""
    if not isinstance(name, str) or not NAME_PATTERN.fullmatch(name) or name in RESERVED:
        raise ValueError(f"--name must match {NAME_PATTERN.pattern} (lower-case letters, digits, '_', '-') "
                         f"and not be one of {sorted(RESERVED)}; got {name!r}")
    return name


def named_dir(name: str) -> Path:
    """The build area of ``name``: ``<reproduction build area>/<name>``."""
    return paths.build_dir() / check_name(name)


@contextmanager
def entered(name: str | None) -> Iterator[None]:
    """Within the block, :func:`sss_locus.paths.build_dir` is the area of ``name`` (no-op for
    ``None``): the run context's build area (:mod:`sss_locus.pipeline.run.context`), which child
    processes get in their context file. The context is restored afterwards."""
    ctx = context.current()
    if name is not None:
        if ctx.build_name is not None:
            raise ValueError(f"--name {name!r}: this process already works in the build area "
                             f"{ctx.build_name!r} ({ctx.build_dir})")
        ctx = ctx.replace(build_dir=named_dir(name), build_name=name)
    with context.use(ctx):
        yield


def differs_from_paper(entry: Any, parameters: Mapping[str, Any]) -> list[str]:
    """How a run of ``entry`` (a registry entry) with ``parameters`` leaves the paper's inputs:
    user data files, ``--set`` overrides, a ``platforms`` list other than the notebook's default,
    another observations or area file than the shipped example.
    Empty for the paper's inputs."""
    declared = entry.parameters()
    out = []
    if parameters.get("data_files"):
        out.append("reads data file(s) " + ", ".join(os.path.basename(f) for f in parameters["data_files"]))
    if parameters.get("data_set"):
        out.append("overrides " + ", ".join(parameters["data_set"]))
    if "observations" in declared and "observations" in parameters:
        from sss_locus.pipeline.run.userfiles import observation_parameters

        default = observation_parameters(declared["observations"].default)["observations"]
        if observation_parameters(parameters["observations"])["observations"] != default:
            out.append(f"reads the observations {os.path.basename(str(parameters['observations']))} "
                       "instead of the worked example")
    if "area" in declared and "area" in parameters:
        from sss_locus.pipeline.run.userfiles import area_parameters

        if area_parameters(parameters["area"])["area"] != area_parameters(declared["area"].default)["area"]:
            out.append(f"plans over the area {os.path.basename(str(parameters['area']))} instead of the example area")
    if "platforms" in declared:
        default, used = list(declared["platforms"].default), list(parameters.get("platforms", []))
        if used != default:
            out.append(f"runs platforms {used} instead of the paper's {default}")
    return out


def check_reproduction(runs: Iterable[tuple[Any, Mapping[str, Any]]], *, replace: bool = False) -> None:
    """Refuse, before anything starts, runs into the reproduction (no ``--name``) whose inputs are
    not the paper's (:func:`differs_from_paper`), naming the figures they would replace; a no-op
    in a named area, with ``replace`` (``--replace-reproduction``) or once checked
    (the run context's ``reproduction_checked``, which child runs of ``book --jobs N`` inherit)."""
    if paths.build_name() is not None or replace or context.current().reproduction_checked:
        _mark_checked()
        return
    from sss_locus.pipeline.publish import export

    figures = export.load_manifests(paths.figures_dir()) if paths.figures_dir().is_dir() else []
    found, files, replaced = [], [], []
    for entry, parameters in runs:
        files += list(parameters.get("data_files") or [])
        why = differs_from_paper(entry, parameters)
        if why:
            replaced += [m["label"] for m in figures if m.get("notebook") == entry.source_relative]
            found.append(f"{entry.name} {'; '.join(why)}")
    if found:
        stem = re.sub(r"[^a-z0-9_-]+", "_", Path(files[0]).stem.lower()).strip("_-") if files else ""
        name = stem if stem and NAME_PATTERN.fullmatch(stem) and stem not in RESERVED else "my_run"
        more = f" (and {len(found) - 1} more chapter(s))" if len(found) > 1 else ""
        shown = (", ".join(replaced[:3]) + (f" and {len(replaced) - 3} more paper figures" if len(replaced) > 3 else "")
                 if replaced else "the paper's chapters")
        raise ValueError(  # one line: the flag first, then why
            f"add --name NAME (e.g. --name {name}) to run on inputs other than the paper's: {found[0]}{more}, "
            f"and without a name it would replace {shown} in the reproduction ({paths.build_dir()}); "
            f"--name {name} puts it in {paths.build_dir() / name} (--replace-reproduction overwrites the "
            "reproduction on purpose).")
    _mark_checked()


def _mark_checked() -> None:
    """The rest of the command (its :func:`entered` block) and its child runs: checked."""
    context.amend(reproduction_checked=True)
