"""A user's own files given as notebook parameters (not ``--data`` TOML files): resolved to
absolute paths and hashed, so that a run's key changes when their bytes do."""

from __future__ import annotations

import hashlib
from pathlib import Path

from sss_locus import paths
from sss_locus.pipeline.run import context
from sss_locus.pipeline.publish import provenance


def _unquote(text: str) -> str:
    """``text`` without surrounding quotes (``-p observations '"my.csv"'``, a string literal)."""
    text = str(text).strip()
    if len(text) >= 2 and text[0] == text[-1] and text[0] in "\"'":
        text = text[1:-1]
    return text


def _resolve(path: str) -> Path:
    """``path`` relative to the folder the command was started in (the run context's
    ``caller_dir``), else to the repository (where the worked
    example lives): relative to the repository when inside it (the same on every checkout),
    otherwise absolute; as given when not found (the reader then names it). Quotes around it
    (``-p observations '"my.csv"'``, a Python string literal) are removed."""
    given = Path(_unquote(path)).expanduser()
    found = next((p for p in (context.current().caller_dir / given, paths.REPO_ROOT / given) if p.is_file()), None)
    if found is None:
        return given
    found = found.resolve()
    return found.relative_to(paths.REPO_ROOT) if found.is_relative_to(paths.REPO_ROOT) else found


def observation_parameters(path: str, truth: str | None = None) -> dict[str, str]:
    """A notebook's ``observations`` file (a user's sightings CSV or XTF matches file) as an
    absolute path (relative to the current directory, else to the repository, where the worked
    example lives) and ``observations_sha256``, the hash of its bytes and of the XTF files it
    names (and of ``truth``, resolved the same way, when given): an edited file makes the run
    stale, as an edited ``--data`` file does."""
    from sss_locus.experiments.sonar_files.observations_xtf import observation_files

    found = _resolve(path)
    files = observation_files(paths.REPO_ROOT / found)
    out = {"observations": str(found)}
    truth = _unquote(truth) if truth is not None else None
    if truth is not None and not truth:
        out["truth"] = ""
    if truth:  # the known positions a synthetic example is compared with
        out["truth"] = str(_resolve(truth))
        files += [paths.REPO_ROOT / out["truth"]] if (paths.REPO_ROOT / out["truth"]).is_file() else []
    digest = hashlib.sha256()
    for f in files:
        digest.update(provenance.file_sha256(f).encode())
    out["observations_sha256"] = digest.hexdigest()
    return out


def file_warnings(parameters: dict) -> list[str]:
    """The one-line warnings of a run's user files that are read only in part: each XTF file
    of the ``observations`` cut short inside its last packet (its complete pings are read;
    :func:`~sss_locus.experiments.sonar_files.observations_xtf.observation_warnings`). ``[]``
    for a run without observations."""
    from sss_locus.experiments.sonar_files.observations_xtf import observation_warnings

    if "observations_sha256" not in parameters or not parameters.get("observations"):
        return []
    return observation_warnings(paths.REPO_ROOT / parameters["observations"])


def area_parameters(path: str) -> dict[str, str]:
    """A notebook's ``area`` file (the survey-design chapter's polygon, TOML or GeoJSON), found
    like the observations (relative to the current directory, else to the repository), and
    ``area_sha256``, the hash of its bytes ("" when there is no such file: the chapter's reader
    names it): an edited area makes the run stale."""
    found = _resolve(path)
    full = paths.REPO_ROOT / found
    if not full.is_file():
        return {"area": str(found), "area_sha256": ""}
    digest = provenance.file_sha256(full)
    grid = _bathymetry_file(full)
    if grid is not None and grid.is_file():  # the area's bathymetry grid: an edited grid makes the run stale too
        digest = hashlib.sha256((digest + provenance.file_sha256(grid)).encode()).hexdigest()
    return {"area": str(found), "area_sha256": digest}


def _bathymetry_file(area_file: Path) -> Path | None:
    """The bathymetry grid an area file names (``bathymetry``, relative to it), or ``None``; an
    unreadable file gives ``None`` (the chapter's reader names what is wrong)."""
    import json
    import tomllib

    try:
        if area_file.suffix.lower() in (".geojson", ".json"):
            doc = json.loads(area_file.read_text(encoding="utf-8-sig"))
            doc = doc.get("properties") or (doc.get("features") or [{}])[0].get("properties") or {}
        else:
            doc = tomllib.loads(area_file.read_text(encoding="utf-8")).get("area", {})
        name = doc.get("bathymetry")
    except (ValueError, AttributeError, TypeError, IndexError, OSError, RecursionError):
        return None
    return (area_file.parent / Path(name).expanduser()) if isinstance(name, str) and name.strip() else None


def file_parameters(parameters: dict) -> dict[str, str]:
    """The parameters of a run that name a user's files (``observations``, ``area``, each with
    its ``*_sha256`` parameter), resolved and hashed (:func:`observation_parameters`,
    :func:`area_parameters`), after reading the files as the chapter will (:func:`check_files`)."""
    out = {}
    for name in ("observations", "area"):
        if name in parameters and f"{name}_sha256" in parameters and not _unquote(str(parameters[name])):
            raise ValueError(f"-p {name}: the path is empty; give the {name} file's name")
    if "observations" in parameters and "observations_sha256" in parameters:
        out.update(observation_parameters(parameters["observations"], parameters.get("truth")))
    if "area" in parameters and "area_sha256" in parameters:
        out.update(area_parameters(parameters["area"]))
    check_files({**parameters, **out})
    return out


def check_files(parameters: dict) -> None:
    """Read the user's files of a run (:func:`file_parameters`) as its chapter will, before a
    kernel starts: a bad area (not a valid polygon, no water depth, no line of a platform's
    standard plan, over the memory or time budget: :mod:`sss_locus.pipeline.run.budgets`), bad
    observations (a row, column or XTF byte offset, a sighting far from the frame's origin), a
    bad ``origin`` or ``truth`` file are refused in one line naming the parameter. The data files (``--data``) must be in use (they define the platforms)."""
    name = "area" if "area_sha256" in parameters else "observations" if "observations_sha256" in parameters else None
    if name is None or name not in parameters:
        return
    given = Path(parameters[name])  # resolved (file_parameters), or as typed when not found
    path = paths.REPO_ROOT / given if (paths.REPO_ROOT / given).is_file() else given
    if not path.is_file():  # say what it is: a folder, a FIFO, a device ...
        from sss_locus.experiments.datamodel.inputs import missing_file

        raise ValueError(f"-p {name}: {missing_file(path, f'{name} file')}")
    try:
        if name == "area":
            from sss_locus.experiments.survey_design import front as sd
            from sss_locus.experiments.datamodel.platforms import load_platform
            from sss_locus.experiments.survey_design.area import load_area
            from sss_locus.experiments.survey_design.settings import load_settings
            from sss_locus.pipeline.run.budgets import check_survey_design

            area = load_area(path)
            if parameters.get("water_depth_m"):
                from sss_locus.experiments.survey_design.area import with_water_depth

                area = with_water_depth(area, parameters["water_depth_m"], "-p water_depth_m")
            platforms = [load_platform(key) for key in parameters.get("platforms", [])]
            check_survey_design(parameters, area, platforms, load_settings())  # before the features are drawn
            for platform in platforms:
                sd.standard_for(sd.make_setting(platform, area, parameters["terrain"], seed=parameters["seed"],
                                                n_features=parameters["n_features"], grid_m=parameters["grid_m"]))
        else:
            from sss_locus.experiments.sonar_files.observations import frame_from_origin, to_local_frame
            from sss_locus.experiments.your_pings.study import read_checked
            from sss_locus.experiments.your_pings.files import read_truth

            table, _ = read_checked(path, missing_attitude=parameters["missing_attitude"],
                                    range_sigma_m=parameters["range_sigma_m"],
                                    **{k: parameters[k] for k in ("sample_order", "towfish") if k in parameters})
            from sss_locus.experiments.passes.pass_noise import load_pass_noise

            for key in table["platform"].unique():  # the joint adjustment reads each platform's [noise.<key>]
                load_pass_noise(str(key))
            # a file where no feature is seen twice is valid: each feature gets its flat-seafloor
            # positions and the status "one sighting: no locus" (issue 36)
            name, observed, path = "origin", path, Path("")
            frame = frame_from_origin(parameters.get("origin"))
            name, path = "observations", observed
            to_local_frame(table, frame)  # every sighting near the frame's origin
            if parameters.get("truth"):
                name = "truth"
                truth = Path(parameters["truth"])
                path = truth if truth.is_absolute() else paths.REPO_ROOT / truth
                read_truth(path, observed)
    except ValueError as exc:
        shown = path.name if path.name and path.name not in str(exc) else ""  # the file, once
        raise ValueError(f"-p {name}{' ' + shown if shown else ''}: {exc}") from None
