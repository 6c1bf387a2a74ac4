"""The data a run reads: the shipped ``data/*.toml`` merged with a user's files and overrides.

A user file (``sss-locus run/book --data FILE.toml``, or the notebook parameter ``data_files``)
has the schema of ``data/*.toml``: its ``sonars``, ``platforms``, ``envelopes``,
``offset_models``, ``noise``, ``terrain`` and ``survey`` tables add to or override the shipped
ones **by key**, at any depth, so a file may hold a whole new platform or a single value::

    [platforms.auv.transducers.port.tilt_deg]
    value = 15.0
    assumption = "our own mounting"

A number (``{value = ..., source|assumption = ...}``) is always replaced whole, so a replaced
value never keeps the shipped file's source. ``--set KEY.PATH=VALUE`` (the notebook parameter
``data_set``) is the quick form for one value; it is recorded as the assumption
``"user override: --set KEY.PATH=VALUE"``. Later files and overrides win over earlier ones.

The active inputs (:func:`use`) are module state, set once per process: the command line sets
them before it validates parameters, and a notebook's imports cell calls
``userdata.use(data_files, data_set)``; the loaders (:func:`sss_locus.experiments.datamodel.platforms.load_platforms`,
:func:`sss_locus.experiments.datamodel.envelopes.load_envelope`,
:func:`sss_locus.experiments.datamodel.noise_model.load_noise_model`,
:func:`sss_locus.experiments.datamodel.terrain.load_terrain_config`) read :func:`document`.
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path
from typing import Any

from sss_locus.paths import public_path
from sss_locus.experiments.datamodel import datadoc, schema
from sss_locus.experiments.datamodel import inputs as inputs_module
from sss_locus.experiments.datamodel.datadoc import (KEY_PATTERN, SET_NOTE, SHIPPED_FILES, USER_TABLES, DataInputs, activate, active,  # noqa: F401
                                                     check_user_document, document, file_sha256, files_read, label_key, make_inputs,
                                                     merge, parse_set, shipped_document)
from sss_locus.experiments.datamodel.models import validate_document
from sss_locus.experiments.datamodel.envelopes import envelope_from, parse_envelope
from sss_locus.experiments.datamodel.platforms import parse_platforms, platforms_from


def validate(inputs: DataInputs) -> dict[str, Any]:
    """Read and validate everything ``inputs`` resolve to; return the merged document.

    Raises ``ValueError`` naming the file or the full key path of the first bad entry: unknown
    keys (with the nearest known one; :mod:`sss_locus.experiments.datamodel.models`) and
    impossible hardware (:mod:`sss_locus.experiments.datamodel.schema`) included.

    Parameters
    ----------
    inputs : DataInputs
        User files and ``--set`` overrides (:func:`~sss_locus.experiments.datamodel.datadoc.make_inputs`).

    Returns
    -------
    dict
        The merged document (shipped data, then the files, then the overrides). An error
        about an entry a user file or override defines says which one.
    """
    for path in inputs.files:
        if Path(path).is_dir():
            raise ValueError(f"data file {path} is a directory, not a TOML file")
        if not Path(path).is_file():
            raise ValueError(inputs_module.missing_file(path, "data file"))
    try:
        doc = document(inputs)
        data = validate_document(doc, USER_TABLES)  # the whole schema (datamodel.models), once
        schema.check_hardware(platforms_from(data), {key: envelope_from(data, key) for key in data.envelopes})
    except ValueError as exc:
        origin = _origin(str(exc), inputs)
        if origin:
            raise ValueError(f"{exc} ({origin})") from None
        raise
    return doc


def _origin(message: str, inputs: DataInputs) -> str:
    """Where the entry a validation ``message`` names came from: the last ``--set`` or user
    file that defines its key path (at least table and key, e.g. ``platforms.my_auv``); ``""``
    if none does (the entry is shipped data, or the message names no key path)."""
    words = message.split(" ", 1)[0].rstrip(":").split(".")
    if len(words) < 2:
        return ""
    full = ".".join(words)
    for item in reversed(inputs.sets):
        key = item.split("=", 1)[0]
        if full == key or full.startswith(key + ".") or key.startswith(full + "."):
            return f"set by --set {item}"
    for path in reversed(inputs.files):
        try:
            node: Any = datadoc.read_toml(path)
        except (OSError, ValueError):
            continue
        for part in words[:2]:
            node = node.get(part) if isinstance(node, dict) else None
        if node is not None:
            return f"from data file {path}"
    return ""


def directory_files(folder: str | Path, what: str = "data directory") -> list[Path]:
    """The data files of a user's data directory: its ``*.toml`` files, in name order.

    A data directory (``sss-locus --data-dir DIR`` or ``$SSS_LOCUS_DATA_DIR``) is a folder of
    files in the schema of ``data/*.toml``, layered over the shipped data exactly as if each were
    given with ``--data`` (name order, before the ``--data`` files: later ones win). Hidden
    files and sub-folders are not read.

    Parameters
    ----------
    folder : str or pathlib.Path
        The directory (``~`` expanded).
    what : str
        How the error names it (e.g. ``"data directory (SSS_LOCUS_DATA_DIR)"``).

    Returns
    -------
    list of pathlib.Path
        Absolute paths of its TOML files, sorted by name; never empty.

    Raises
    ------
    ValueError
        In one line naming ``folder``: it does not exist, is not a folder, cannot be read, or
        holds no ``.toml`` file.
    """
    path = Path(folder).expanduser()
    if not str(folder).strip():
        raise ValueError(f"{what} is empty: give a folder of TOML data files")
    if not path.exists():
        raise ValueError(f"{what} {path} does not exist")
    if not path.is_dir():
        raise ValueError(f"{what} {path} is not a folder (give a single file with --data)")
    try:
        found = sorted(p.resolve() for p in path.iterdir() if p.suffix == ".toml" and not p.name.startswith("."))
    except OSError as exc:
        raise ValueError(f"{what} {path} cannot be read ({exc.strerror or exc})") from None
    if not found:
        raise ValueError(f"{what} {path} holds no .toml file (it takes TOML files in the schema of data/*.toml)")
    return found


def use(data_files: Iterable[str | Path] = (), data_set: Iterable[str] = ()) -> DataInputs:
    """Validate and activate user data for this process (a notebook calls this with its
    ``data_files`` and ``data_set`` parameters); return the active :class:`DataInputs`.

    Parameters
    ----------
    data_files : iterable of str or pathlib.Path
        User TOML data files, merged in order over the shipped data.
    data_set : iterable of str
        ``KEY.PATH=VALUE`` overrides, applied last, in order.

    Returns
    -------
    DataInputs
        The inputs now active (nothing is activated when validation raises ``ValueError``).
    """
    inputs = make_inputs(data_files, data_set)
    validate(inputs)
    activate(inputs)
    return inputs


def hardware_flags(inputs: DataInputs | None = None) -> list[str]:
    """Values of ``inputs`` that are possible but look like a mistake (e.g. a tilt in radians),
    one line each (:func:`sss_locus.experiments.datamodel.schema.hardware_warnings`). A fan that reaches
    above the horizontal or past the vertical (:func:`~sss_locus.experiments.datamodel.schema.fan_warnings`)
    is flagged for the user's platforms only, not where the shipped platform of that key does it
    already (the paper's AUV: a 130 deg fan at 25.5 deg look-down).

    Parameters
    ----------
    inputs : DataInputs, optional
        Default: the active inputs.

    Returns
    -------
    list of str
        Warning lines naming the data entry; empty for the shipped data.
    """
    doc = document(inputs)
    platforms = parse_platforms(doc)
    envelopes = {key: parse_envelope(doc, key) for key in doc.get("envelopes", {}) if key in platforms}
    shipped = {kind for kind, _ in schema.fan_warnings(parse_platforms(datadoc.shipped_document()))}
    user_fans = {line for kind, line in schema.fan_warnings(platforms) if kind not in shipped}
    all_fans = {line for _, line in schema.fan_warnings(platforms)}
    return [line for line in schema.hardware_warnings(platforms, envelopes) if line not in all_fans or line in user_fans]


def resolved_values(platform_keys: Iterable[str], inputs: DataInputs | None = None, *,
                    envelopes: bool | Iterable[str] = True) -> dict[str, Any]:
    """The sonar, mounting and envelope values the named platforms resolve to (for manifests);
    the envelope only for ``envelopes`` (True: every platform, else the keys listed).

    Parameters
    ----------
    platform_keys : iterable of str
        Platform keys; keys the data do not define are skipped.
    inputs : DataInputs, optional
        Default: the active inputs.
    envelopes : bool or iterable of str
        Which platforms' survey envelopes to include (False: none).

    Returns
    -------
    dict
        Platform key -> ``name``, ``sonar`` (key, name, full apertures ``azimuth_deg`` and
        ``elevation_deg``, ``max_range_m``, ``min_range_m``), ``tilt_deg`` by side,
        ``attitude_max_deg`` (roll, pitch), ``depth_m`` ``[min, max]``, optionally ``envelope``
        and ``set_by_user`` (fields set by ``--set``). The entries read are noted
        (:func:`~sss_locus.experiments.datamodel.datadoc.note_read`).
    """
    doc = document(inputs)
    platforms = parse_platforms(doc)
    out: dict[str, Any] = {}
    for key in platform_keys:
        if key not in platforms:
            continue
        p = platforms[key]
        with_envelope = envelopes is True or (envelopes is not False and key in set(envelopes))
        datadoc.note_read(  # a figure's manifest records these values: the run reads them
            f"platforms.{key}", f"sonars.{p.sonar.key}", *([f"envelopes.{key}"] if with_envelope else []))
        s = p.sonar
        entry: dict[str, Any] = {
            "name": p.name,
            "sonar": {"key": s.key, "name": s.name, "azimuth_deg": s.azimuth_deg,
                      "elevation_deg": s.elevation_deg, "max_range_m": s.max_range_m,
                      "min_range_m": s.min_range_m},
            "tilt_deg": {side: t.tilt_deg for side, t in p.transducers.items()},
            "attitude_max_deg": {"roll": p.roll_max_deg, "pitch": p.pitch_max_deg},
            "depth_m": [p.depth_min_m, p.depth_max_m],
        }
        if with_envelope and key in doc.get("envelopes", {}):
            entry["envelope"] = parse_envelope(doc, key).key()
        user = sorted(k for k, v in p.provenance.items() if v.startswith("assumption: " + SET_NOTE))
        if user:
            entry["set_by_user"] = user
        out[key] = entry
    return out


def record(platform_keys: Iterable[str] = (), inputs: DataInputs | None = None) -> dict[str, Any]:
    """The data-input record of a run: files read with SHA-256, overrides, resolved values.

    Parameters
    ----------
    platform_keys : iterable of str
        Platforms whose resolved values are recorded.
    inputs : DataInputs, optional
        Default: the active inputs.

    Returns
    -------
    dict
        ``files`` (:func:`~sss_locus.experiments.datamodel.datadoc.files_read`), ``overrides``
        (the ``--set`` texts) and ``values`` (:func:`resolved_values`).
    """
    inputs = active() if inputs is None else inputs
    return {"files": files_read(inputs), "overrides": list(inputs.sets),
            "values": resolved_values(platform_keys, inputs)}


#: Tables read whole (not per platform); a figure's record names them when its run read them.
WHOLE_TABLES = ("terrain", "survey", "survey_design")


def figure_record(platform_keys: Iterable[str], inputs: DataInputs | None = None,
                  read: Iterable[str] | None = None) -> dict[str, Any]:
    """The data one figure was computed from: exactly the platforms it shows, with their entries.

    Parameters
    ----------
    platform_keys : iterable of str
        The platforms the figure shows (a figure per platform: one; a figure combining
        platforms: each of them).
    inputs : DataInputs, optional
        The run's data inputs (default: the active ones).
    read : iterable of str, optional
        The data entries the run has read so far (:func:`sss_locus.experiments.datamodel.datadoc.reads_so_far`);
        a platform's ``envelopes``/``noise`` entries and the ``offset_models`` count only when read.
        ``None`` (outside the runner): every entry the platforms have.

    Returns
    -------
    dict
        ``platforms`` (the keys), ``entries`` (each dotted data entry with the SHA-256 of its merged
        value: ``platforms.<key>``, ``sonars.<sonar>``, ``envelopes.<key>``, ``noise.<key>``,
        ``offset_models.<model>``, and the whole tables of :data:`WHOLE_TABLES` the run read),
        ``files`` (the data files that define any of these entries,
        ``{"path", "sha256", "role"}``), ``overrides`` (the ``--set`` values inside them) and
        ``values`` (:func:`resolved_values` of the platforms).
    """
    inputs = active() if inputs is None else inputs
    keys = [k for k in dict.fromkeys(platform_keys) if isinstance(k, str)]
    doc = document(inputs)
    read = None if read is None else set(read)

    def wanted(entry: str) -> bool:
        table, _, key = entry.partition(".")
        return key in doc.get(table, {}) and (read is None or entry in read)

    envelopes = [k for k in keys if wanted(f"envelopes.{k}")]
    values = resolved_values(keys, inputs, envelopes=envelopes)
    entries = [e for k, v in values.items()
               for e in (f"platforms.{k}", f"sonars.{v['sonar']['key']}", f"envelopes.{k}", f"noise.{k}")
               if e.startswith(("platforms.", "sonars.")) or wanted(e)]
    entries += sorted(e for e in (read or ()) if e.startswith("offset_models.") and values)
    entries += sorted(e for e in (read or ()) if e in WHOLE_TABLES and e in doc)
    hashes = datadoc.entries_sha256(entries, inputs)

    def defines(path: str) -> bool:
        try:
            own = datadoc.read_toml(datadoc.DATA_DIR / path.removeprefix("data/") if path.startswith("data/") else path)
        except (OSError, ValueError):
            return True  # unreadable now: keep it listed rather than hide an input
        return any((e in own) if "." not in e else e.partition(".")[2] in (own.get(e.partition(".")[0]) or {})
                   for e in entries)

    def inside(override: str) -> bool:
        key = override.split("=", 1)[0].strip()
        return any(key == e or key.startswith(e + ".") for e in entries)

    return {"platforms": list(values), "entries": hashes,
            "files": [{**f, "path": public_path(f["path"]) if f["role"] == "user" else f["path"]}
                      for f in files_read(inputs) if defines(f["path"])],
            "overrides": [o for o in inputs.sets if inside(o)], "values": values}


def describe_platform(key: str, inputs: DataInputs | None = None) -> str:
    """One line naming a platform's sonar, aperture, range and tilt (for captions).

    Parameters
    ----------
    key : str
        A platform key of the data.
    inputs : DataInputs, optional
        Default: the active inputs.

    Returns
    -------
    str
        E.g. ``"<platform>: <sonar>, 130° × 0.27°, 150 m, tilt 25.5°"`` (full apertures in
        degrees, maximum range in metres, the distinct tilts of its sides joined by ``/``).

    Raises
    ------
    KeyError
        ``key`` is not a platform of the data.
    """
    values = resolved_values([key], inputs)[key]
    s, tilts = values["sonar"], sorted(set(values["tilt_deg"].values()))
    tilt = "/".join(f"{t:g}" for t in tilts)
    return (f"{values['name']}: {s['name']}, {s['azimuth_deg']:g}° × {s['elevation_deg']:g}°, "
            f"{s['max_range_m']:g} m, tilt {tilt}°")


def _leaf_differences(a: Any, b: Any, path: str) -> list[str]:
    """Dotted paths under ``path`` where ``a`` and ``b`` differ (a number entry counts as a leaf)."""
    if isinstance(a, dict) and isinstance(b, dict) and "value" not in a and "value" not in b:
        return [d for k in sorted(set(a) | set(b)) for d in _leaf_differences(a.get(k), b.get(k), f"{path}.{k}")]
    return [] if a == b else [path]


def changed_from_shipped(platform_keys: Iterable[str], inputs: DataInputs | None = None,
                         tables: Iterable[str] = ()) -> list[str]:
    """The data entries that the named platforms read and ``inputs`` change from the shipped data.

    For each key: its ``platforms``, ``envelopes`` and ``noise`` tables and its sonar's table, and
    the ``offset_models`` every survey study reads; then the shared ``tables`` a run read (e.g.
    ``terrain`` and ``survey``, which only the reconstruction chapter reads); as dotted key paths
    (e.g. ``platforms.auv.transducers.port.tilt_deg``), or ``platforms.<key>`` for a key the
    shipped data do not have. Empty when the platforms read exactly the shipped values.

    Parameters
    ----------
    platform_keys : iterable of str
        The platforms a run used.
    inputs : DataInputs, optional
        Default: the active inputs.
    tables : iterable of str
        Shared tables the run read (compared whole).

    Returns
    -------
    list of str
        Dotted key paths, without repeats, in the order found.
    """
    doc, shipped = document(inputs), shipped_document()
    found: list[str] = []
    marked = {f"{t}.{k}.name" for t in datadoc.NAMED_TABLES for k, e in doc.get(t, {}).items()
              if k in shipped.get(t, {}) and isinstance(e, dict)
              and datadoc.is_changed_name(e.get("name", ""), shipped[t][k].get("name", ""))}
    for key in platform_keys:
        if key not in shipped.get("platforms", {}):
            found.append(f"platforms.{key}")
            continue
        sonars = {doc["platforms"].get(key, {}).get("sonar"), shipped["platforms"][key].get("sonar")}
        paths = [("platforms", key), *(("sonars", s) for s in sorted(sonars) if isinstance(s, str)),
                 ("envelopes", key), ("noise", key)]
        for table, name in paths:
            found += _leaf_differences(doc.get(table, {}).get(name), shipped.get(table, {}).get(name),
                                       f"{table}.{name}")
    found += _leaf_differences(doc.get("offset_models"), shipped.get("offset_models"), "offset_models")
    for table in tables:
        found += _leaf_differences(doc.get(table), shipped.get(table), table)
    return [f for f in dict.fromkeys(found) if f not in marked]  # a marked name is no change of its own
