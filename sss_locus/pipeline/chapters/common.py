"""Helpers every chapter facade re-exports: the run's data, a table shown and published in one
call, and glue keys filled from declared templates.

Glue keys: each facade declares its chapter's key templates as constants of a ``KEYS`` class
(``KEYS.deepest = "wa-{platform}-deepest-m"``) and a notebook fills them with :func:`key`, so a
key seen in the book (``wa-auv-deepest-m``) is found back in the code by searching its fixed
parts (``-deepest-m``), never built by an f-string in a notebook.
"""

from __future__ import annotations

import string
from collections.abc import Sequence
from typing import Any

import pandas as pd

from sss_locus.experiments.datamodel import userdata
from sss_locus.experiments.datamodel.datadoc import label_key
from sss_locus.pipeline.publish.publish import publish_table
from sss_locus.report.common.tables import files_note, readable_table

_KEY_SEPARATORS = set(" \t\n`")  # a filled key holds no whitespace and no backtick (MyST roles)


def use_data(data_files: Sequence[str] = (), data_set: Sequence[str] = ()) -> userdata.DataInputs:
    """Validate the user's data files and ``KEY.PATH=VALUE`` overrides (the notebook's
    ``data_files`` and ``data_set`` parameters) and make them the data this kernel reads
    (:func:`sss_locus.experiments.datamodel.userdata.use`); returns them.

    The activation is process-wide (every loader of ``experiments`` reads the active data):
    call it once, in the import cell, before anything is loaded.
    """
    return userdata.use(data_files, data_set)


def show_table(frame: pd.DataFrame, label: str, *, caption: str, shown: pd.DataFrame | None = None,
               platforms: Sequence[str] | None = None, input_files: Sequence[Any] = (), publish: bool = True,
               **readable: Any) -> None:
    """Publish ``frame`` as the citable table ``label`` and display it, with one caption.

    Parameters
    ----------
    frame : pandas.DataFrame
        The table as published (its CSV holds every row and column).
    label : str
        ``tab-`` plus lower-case words joined by hyphens.
    caption : str
        The caption without its files sentence: :func:`sss_locus.report.common.tables.files_note` of
        ``label`` is appended, in the published and in the shown caption alike (when published).
    shown : pandas.DataFrame, optional
        The part of ``frame`` shown in the chapter (e.g. only the rows that changed), when not
        all of it; it is still ``frame`` that is published.
    platforms, input_files
        As for :func:`sss_locus.pipeline.publish.publish.publish_table`.
    publish : bool
        False: only show ``frame`` (a table with no rows in this run is not published, and its
        caption then names no files).
    **readable
        Passed to :func:`sss_locus.report.common.tables.readable_table` (``digits``, ``headers``,
        ``row_labels``).
    """
    from IPython.display import display

    if not publish:
        display(readable_table(frame if shown is None else shown, caption=caption, **readable))
        return
    full = f"{caption} {files_note(label)}" if caption else files_note(label)
    publish_table(frame, label, caption=full, platforms=platforms, input_files=input_files)
    display(readable_table(frame if shown is None else shown, caption=full, **readable))


def key(template: str, **fields: Any) -> str:
    """The glue key ``template`` names, its ``{fields}`` filled.

    Parameters
    ----------
    template : str
        One of a facade's ``KEYS`` templates, e.g. ``"wa-{platform}-deepest-m"``.
    **fields
        A value for every field of the template and no other. A ``platform`` field takes a
        data key (``my_auv``) and is written as in figure labels (``my-auv``,
        :func:`sss_locus.experiments.datamodel.datadoc.label_key`); other values are written with
        ``str``.

    Returns
    -------
    str
        The filled key.

    >>> key("wa-{platform}-deepest-m", platform="my_auv")
    'wa-my-auv-deepest-m'
    """
    names = {f for _, f, _, _ in string.Formatter().parse(template) if f is not None}
    if names != set(fields):
        raise ValueError(f"glue key template {template!r} needs the fields {sorted(names)}; "
                         f"got {sorted(fields)}")
    values = {k: label_key(v) if k == "platform" else str(v) for k, v in fields.items()}
    out = template.format(**values)
    bad = sorted(set(out) & _KEY_SEPARATORS)
    if bad or not out:
        raise ValueError(f"glue key {out!r} (template {template!r}) is empty or holds characters {bad} "
                         "(whitespace or a backtick end a MyST role)")
    return out


def paper_platforms(chapter: str) -> list[str]:
    """The paper's platforms of a chapter: the default of its ``platforms`` parameter
    (:mod:`sss_locus.pipeline.chapters.params`), for
    :func:`~sss_locus.report.common.text.run_platforms_md`.

    Parameters
    ----------
    chapter : str
        The notebook's name (``"pose_space"``).

    Returns
    -------
    list of str
        Platform keys; empty for a chapter without a ``platforms`` parameter.

    >>> paper_platforms("pose_space")
    ['auv', 'boat']
    """
    from importlib import import_module

    field = import_module(f"sss_locus.pipeline.chapters.params.{chapter}").Params.model_fields.get("platforms")
    return list(field.default) if field is not None else []


def templates(keys: type) -> dict[str, str]:
    """The templates a facade's ``KEYS`` class declares (attribute name -> template)."""
    return {k: v for k, v in vars(keys).items() if not k.startswith("_") and isinstance(v, str)}


__all__ = ["key", "paper_platforms", "show_table", "templates", "use_data"]
