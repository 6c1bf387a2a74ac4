"""Citable figure export: image files, plotted data, a provenance manifest and a BibTeX entry.

Notebooks publish figures with :func:`sss_locus.pipeline.publish.publish.publish`, which calls
:func:`export_figure` with the run's parameters, glues the figure and its caption and closes it::

    from sss_locus.pipeline.publish.publish import publish

    publish(fig, "fig-locus-concept", data=points_frame, caption=caption)

and the notebook places the figure with ``{glue:figure} fig-locus-concept`` and
``:name: fig-locus-concept`` in a markdown cell of the *same* notebook.

Where it writes (:func:`default_out_dir`): into the run context's ``figures_dir`` when the
runner set it (``sss-locus run`` / ``book`` point it at the run's private staging folder and move the
figures into the build area, :func:`sss_locus.paths.figures_dir`, only when the whole run
succeeded), otherwise into ``figures/`` beside the run (the kernel's working directory, which
``papermill --cwd`` sets to the output's folder). A plain papermill run or an interactive session
therefore never writes into the build area. Each file is written to a unique temporary name and
renamed, so two writers of one label never share a temporary file. The files:

``<label>.png`` (``dpi`` >= 200), ``<label>.svg``, ``<label>.pdf``
    The figure (vector formats without timestamps, so reruns are byte-comparable).
``<label>.csv`` or ``<label>--<name>.csv``
    The plotted data: one file for a DataFrame, one per entry for a dict of DataFrames.
``<label>.bib``
    A "cite this figure" BibTeX entry.
``<label>.json``
    The manifest, written last (atomically): label, caption, notebook, profile, parameters, seed,
    git commit, lock-file hash, package version, run time (UTC), the data inputs
    (:func:`data_inputs`: data files with SHA-256, overrides, resolved platform values), the
    smallest drawn text and the picture's width (``text``, see
    :mod:`sss_locus.pipeline.publish.readability`) and every file with its SHA-256.
    A figure without a manifest is incomplete and is ignored by :func:`load_manifests`.
"""

from __future__ import annotations

import io
import json
import os
import re
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from sss_locus import paths
from sss_locus.pipeline.run import atomic, context
from sss_locus.pipeline.publish import citation, provenance, readability

if TYPE_CHECKING:  # pandas is imported where a figure's data is written: the CLI starts without it
    import pandas as pd

# Used with fullmatch: the whole string must match (``$`` alone would accept a trailing newline).
LABEL_PATTERN = re.compile(r"fig-[a-z0-9]+(?:-[a-z0-9]+)*")
TABLE_LABEL_PATTERN = re.compile(r"tab-[a-z0-9]+(?:-[a-z0-9]+)*")
#: Label prefixes of exported items: figures, and tables (:func:`export_table`).
KINDS = ("fig", "tab")
DATA_NAME_PATTERN = re.compile(r"[a-z0-9]+(?:[_-][a-z0-9]+)*")
#: Names of attached files (e.g. ``mission.plan``): a data name and an extension.
ATTACHMENT_PATTERN = re.compile(DATA_NAME_PATTERN.pattern + r"\.[a-z0-9]+")
#: Set by the runner: the folder a run exports into, and the run key recorded in each manifest.
MIN_DPI = 200
IMAGE_FORMATS = ("png", "svg", "pdf")
# Fixed metadata so that SVG and PDF bytes do not change with the clock.
_SAVE_METADATA = {"svg": {"Date": None}, "pdf": {"CreationDate": None, "ModDate": None}}


def _check_label(label: str) -> None:
    if not isinstance(label, str) or not LABEL_PATTERN.fullmatch(label):
        raise ValueError(
            f"label must look like 'fig-some-name' (lower-case letters, digits, single hyphens; "
            f"pattern {LABEL_PATTERN.pattern}), got {label!r}"
        )


def _normalise_data(label: str, data: pd.DataFrame | Mapping[str, pd.DataFrame]) -> dict[str, pd.DataFrame]:
    """Map CSV file names to frames."""
    import pandas as pd
    if isinstance(data, pd.DataFrame):
        return {f"{label}.csv": data}
    if isinstance(data, Mapping) and data:
        frames = {}
        for name, frame in data.items():
            if not isinstance(name, str) or not DATA_NAME_PATTERN.fullmatch(name):
                raise ValueError(
                    f"data keys must be short names of lower-case letters, digits, '_' or '-', "
                    f"got {name!r}"
                )
            if not isinstance(frame, pd.DataFrame):
                raise ValueError(f"data[{name!r}] must be a pandas DataFrame, got {type(frame).__name__}")
            frames[f"{label}--{name}.csv"] = frame
        return frames
    raise ValueError(
        "data must be a pandas DataFrame or a non-empty dict of DataFrames (the plotted values), "
        f"got {type(data).__name__}"
    )


def default_out_dir() -> Path:
    """The run context's ``figures_dir`` (the runner's staging folder), else ``figures/`` in the
    working directory."""
    given = context.current().figures_dir
    return given if given is not None else Path.cwd() / paths.FIGURES_SUBDIR


def _write_atomic(path: Path, text: str) -> None:
    atomic.write_atomic(path, text)


def _save_atomic(path: Path, save: Any) -> None:
    """``save(tmp)`` to a unique temporary name, then rename it to ``path``."""
    tmp = atomic.temp_name(path)
    try:
        save(tmp)
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)


def data_inputs(parameters: Mapping[str, Any], platforms: Sequence[str] | None = None) -> dict[str, Any]:
    """The data one figure was computed from (:func:`sss_locus.experiments.datamodel.userdata.figure_record`):
    exactly the platforms it shows (``platforms``; default: every platform of the run's
    ``platforms`` parameter), their data entries with SHA-256, the data files that define them
    (with SHA-256), the ``--set`` overrides inside them and their resolved values."""
    from sss_locus.experiments.datamodel import userdata

    keys = parameters.get("platforms", []) if platforms is None else platforms
    keys = [keys] if isinstance(keys, str) else list(keys or [])
    try:
        return userdata.figure_record([k for k in dict.fromkeys(keys) if isinstance(k, str)],
                                      read=userdata.datadoc.reads_so_far())
    except (OSError, ValueError) as exc:  # never lose a figure over its provenance
        return {"error": str(exc)}


def with_files(inputs: dict[str, Any], files: Sequence[Any]) -> dict[str, Any]:
    """``inputs`` with ``files`` (paths, or ``(path, role)``) added to its ``files``: name relative
    to the repository when inside it, else the file name; SHA-256; role (``"observations"``)."""
    extra = []
    for f, role in (f if isinstance(f, tuple) else (f, "observations") for f in files):
        p = Path(f).resolve()
        name = str(p.relative_to(paths.REPO_ROOT)) if p.is_relative_to(paths.REPO_ROOT) else p.name
        extra.append({"path": name, "sha256": provenance.file_sha256(p), "role": role})
    if not extra:
        return inputs
    return {**inputs, "files": [*inputs.get("files", []), *extra]}


def bibtex_entry(manifest: Mapping[str, Any]) -> str:
    """A ``@misc`` BibTeX entry citing one exported figure, from its manifest (every field valid
    LaTeX; see :func:`sss_locus.pipeline.publish.citation.figure_bibtex`)."""
    return citation.figure_bibtex(manifest)


def export_figure(
    fig: Any,
    label: str,
    data: pd.DataFrame | Mapping[str, pd.DataFrame],
    *,
    caption: str,
    parameters: Mapping[str, Any],
    seed: int | None = None,
    notebook: str | None = None,
    cell: int | None = None,
    dpi: int = 300,
    out_dir: Path | None = None,
    shown: list[bytes] | None = None,
    platforms: Sequence[str] | None = None,
    input_files: Sequence[Any] = (),
    attachments: Mapping[str, str] | None = None,
) -> dict[str, Any]:
    """Export one figure with its data, manifest and BibTeX entry; return the manifest.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The finished figure.
    label : str
        Stable label, ``fig-`` followed by lower-case words joined by hyphens
        (e.g. ``"fig-locus-concept"``). Also the ``:name:`` of the figure in the book.
    data : pandas.DataFrame or dict of str to pandas.DataFrame
        The values actually plotted, written as CSV next to the images.
    caption : str
        The figure's caption (MyST/LaTeX math in ``$...$`` allowed); its first sentence (cut
        short) becomes the BibTeX title.
    parameters : mapping
        The notebook parameters the figure depends on (JSON-serialisable; numpy scalars are fine).
    seed : int, optional
        Random seed of the run; defaults to ``parameters["seed"]`` when present.
    notebook : str, optional
        Notebook that drew the figure; defaults to what the runner reports
        (the run context's, :mod:`sss_locus.pipeline.run.context`).
    cell : int, optional
        Execution count (``In [n]``) of the notebook cell that drew the figure; recorded in the
        manifest so that the book links the figure to that cell.
    dpi : int
        Resolution of the PNG, at least 200.
    out_dir : pathlib.Path, optional
        Output folder; defaults to :func:`default_out_dir` (never the build area outside the
        runner).
    shown : list, optional
        If given, the picture a chapter shows is appended to it: PNG bytes at the figure's own
        ``dpi``, from the same layout and tight box as the files (see :func:`_save_images`).
    platforms : sequence of str, optional
        The platforms the figure shows (its data inputs name exactly these, :func:`data_inputs`);
        default: every platform of ``parameters["platforms"]``.
    input_files : sequence of path or of (path, role)
        The user's files the figure was computed from besides the TOML data (a survey's sightings
        and XTF files; ``(path, "area")``: a survey area), recorded in ``data_inputs["files"]``
        with SHA-256 and role (default ``"observations"``) for the BibTeX note and the book.
    attachments : mapping of str to str, optional
        Other files computed with the figure (e.g. the mission files of a survey plan), by name
        (``mission.plan``: :data:`ATTACHMENT_PATTERN`) to text; written as ``<label>--<name>``
        and listed in the manifest like the data, so they are cited and replaced with the figure.

    Returns
    -------
    dict
        The manifest as written to ``<label>.json``.
    """
    _check_label(label)
    if not hasattr(fig, "savefig"):
        raise ValueError(f"fig must be a matplotlib Figure (with .savefig), got {type(fig).__name__}")
    if not isinstance(caption, str) or not caption.strip():
        raise ValueError("caption must be a non-empty string")
    if not isinstance(parameters, Mapping):
        raise ValueError(f"parameters must be a mapping of name to value, got {type(parameters).__name__}")
    if not isinstance(dpi, (int, np.integer)) or dpi < MIN_DPI:
        raise ValueError(f"dpi must be an integer >= {MIN_DPI}, got {dpi!r}")
    frames = _normalise_data(label, data)
    for name, body in (attachments or {}).items():
        if not isinstance(name, str) or not ATTACHMENT_PATTERN.fullmatch(name) or not isinstance(body, str):
            raise ValueError(f"attachments must map names like 'mission.plan' (pattern {ATTACHMENT_PATTERN.pattern}) "
                             f"to text; got {name!r}")
    params = json.loads(json.dumps(dict(parameters), default=provenance.json_default))
    if seed is None and "seed" in params:
        seed = params["seed"]

    out = default_out_dir() if out_dir is None else Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    manifest_path = out / f"{label}.json"
    manifest_path.unlink(missing_ok=True)  # incomplete until the new manifest is written

    import matplotlib  # only here: the package itself does not depend on matplotlib

    written: list[Path] = []
    # A fixed salt makes SVG element ids (random by default) reproducible.
    with matplotlib.rc_context({"svg.hashsalt": label}):
        images, text = _save_images(fig, out, label, int(dpi), shown)
    written.extend(images)
    import pandas as pd
    for name, frame in frames.items():
        index = not isinstance(frame.index, pd.RangeIndex)
        _save_atomic(out / name, lambda tmp, frame=frame, index=index: frame.to_csv(tmp, index=index))
        written.append(out / name)
    for name, body in (attachments or {}).items():
        _write_atomic(out / f"{label}--{name}", body)
        written.append(out / f"{label}--{name}")

    manifest: dict[str, Any] = {
        "label": label,
        "caption": caption.strip(),
        "notebook": notebook or context.current().notebook,
        "cell": int(cell) if isinstance(cell, (int, np.integer)) and cell > 0 else None,
        "profile": context.current().profile,
        "parameters": params,
        "seed": json.loads(json.dumps(seed, default=provenance.json_default)),
        "git_commit": provenance.git_commit(),
        "lock_sha256": provenance.lock_sha256(),
        "package_version": provenance.package_version(),
        "run_time_utc": provenance.utc_now(),
        "dpi": int(dpi),
        "text": text,  # smallest drawn text and picture width: readability on the page
        "run_key": context.current().run_key, "build_area": paths.build_name(),  # its executed copy, area
        "data_inputs": with_files(data_inputs(params, platforms), input_files),
    }
    bib_path = out / f"{label}.bib"
    _write_atomic(bib_path, bibtex_entry(manifest))
    written.append(bib_path)
    manifest["files"] = {
        p.name: {"url": f"{paths.FIGURES_SUBDIR}/{p.name}", "sha256": provenance.file_sha256(p)}
        for p in written
    }
    _write_atomic(manifest_path, json.dumps(manifest, indent=2, sort_keys=True) + "\n")
    return manifest


def _save_images(fig: Any, out: Path, label: str, dpi: int,
                 shown: list[bytes] | None) -> tuple[list[Path], dict[str, Any]]:
    """Write ``<label>.png``, ``.svg`` and ``.pdf`` from ONE layout; return the paths and the
    readability record (:func:`readability.text_record`) of the PNG's draw.

    The PNG is saved exactly as ``fig.savefig(..., bbox_inches="tight")`` saves it (layout
    engine run, dry draw, tight box, draw), and the tight box it computed is kept. The layout is
    then frozen and the vector files (and ``shown``'s picture at the figure's dpi) are drawn
    with that box: one draw each instead of a layout, a dry draw, a tight-box search and a draw.
    They therefore share the PNG's layout (text extents measured by Agg at ``dpi``) to the
    digit, where separate saves would each lay the figure out again with their own renderer's
    text metrics (differences well below a pixel).
    """
    import matplotlib

    boxes: list[Any] = []
    measure = fig.get_tightbbox

    def recording_box(*args, **kwargs):  # called by savefig("tight") once, after the layout
        boxes.append(measure(*args, **kwargs))
        return boxes[-1]

    png = out / f"{label}.png"
    fig.get_tightbbox = recording_box
    try:
        with readability.recording_text() as drawn:  # the PNG is drawn by Agg
            _save_atomic(png, lambda tmp: fig.savefig(tmp, format="png", dpi=dpi, bbox_inches="tight"))
    finally:
        del fig.get_tightbbox
    text = readability.text_record(drawn, _png_width_px(png) / dpi, fig.dpi)
    box = boxes[-1].padded(matplotlib.rcParams["savefig.pad_inches"])
    written = [png]
    engine = fig.get_layout_engine()
    if engine is not None:  # no engine at all (not even "none"): savefig then skips its dry draw
        with matplotlib.rc_context({"figure.autolayout": False, "figure.constrained_layout.use": False}):
            fig.set_layout_engine(None)  # the positions the PNG was drawn with stay
    try:
        for fmt in ("svg", "pdf"):
            target = out / f"{label}.{fmt}"
            _save_atomic(target, lambda tmp, fmt=fmt: fig.savefig(
                tmp, format=fmt, dpi=dpi, bbox_inches=box, metadata=_SAVE_METADATA[fmt]))
            written.append(target)
        if shown is not None:
            buffer = io.BytesIO()
            fig.savefig(buffer, format="png", dpi=fig.dpi, bbox_inches=box)
            shown.append(buffer.getvalue())
    finally:
        if engine is not None:
            fig.set_layout_engine(engine)
    return written, text


def _png_width_px(path: Path) -> int:
    """Pixel width of a PNG file, from its IHDR header."""
    with open(path, "rb") as fh:
        head = fh.read(24)
    if head[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path} is not a PNG file")
    return int.from_bytes(head[16:20], "big")


def load_manifests(out_dir: Path | None = None, kinds: Sequence[str] = ("fig",)) -> list[dict[str, Any]]:
    """Manifests of all complete exported figures (``kinds``: label prefixes, ``"tab"`` for
    tables), sorted by notebook then label.

    A figure counts as complete when its manifest exists and every file it lists is present with
    the recorded SHA-256.
    """
    out = paths.figures_dir() if out_dir is None else Path(out_dir)
    manifests = []
    for path in sorted(p for kind in kinds for p in out.glob(f"{kind}-*.json")):
        manifest = _read_manifest(path)
        files = manifest.get("files", {}) if manifest else {}
        if files and all(isinstance(entry, dict) and provenance.file_sha256(out / name) == entry.get("sha256")
                         for name, entry in files.items()):
            manifests.append(manifest)
    return sorted(manifests, key=lambda m: (m["notebook"], m["label"]))


def _read_manifest(path: Path) -> dict[str, Any] | None:
    """A manifest's contents, or None if it vanished after it was listed.

    Notebooks run in parallel (``sss-locus book --jobs N``) delete and rewrite their own
    figures, so a manifest seen by ``glob`` may be gone by the time it is read.
    """
    try:
        manifest = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):  # vanished, or half-written by a pre-atomic writer
        return None
    if not isinstance(manifest, dict) or not isinstance(manifest.get("files"), dict):
        return None
    return manifest


def remove_figures_of(notebook: str, out_dir: Path | None = None) -> list[str]:
    """Delete every exported figure and table whose manifest names ``notebook``; return their labels.

    The runner calls this before rerunning a notebook so that a figure the notebook no longer
    draws does not linger on the site.
    """
    out = paths.figures_dir() if out_dir is None else Path(out_dir)
    removed = []
    for path in sorted(p for kind in KINDS for p in out.glob(f"{kind}-*.json")):
        manifest = _read_manifest(path)
        if manifest is None or manifest.get("notebook") != notebook:
            continue
        for name in manifest.get("files", {}):
            (out / name).unlink(missing_ok=True)
        path.unlink(missing_ok=True)
        removed.append(manifest["label"])
    return removed
