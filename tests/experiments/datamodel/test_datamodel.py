"""The data model (issue 41): the pydantic schema of the data files against its documentation.

The reference is ``data/README.md``'s table of valid values, written for users: every bound
there is refused just outside and accepted on the bound (a closed end) by the model, and every
sourced value of the model is documented there. Messages name the key path, the value and the
range in one line, and the file or ``--set`` that holds the bad entry.
"""

from __future__ import annotations

import copy
import math
import re
import types
from pathlib import Path
from typing import Union, get_args, get_origin

import pytest
from pydantic import BaseModel

from sss_locus.experiments.datamodel import datadoc, userdata
from sss_locus.experiments.datamodel import models
from sss_locus.experiments.datamodel.sourced import Sourced
from sss_locus.experiments.datamodel.inputs import read_toml

REPO = Path(__file__).resolve().parents[3]
ROW = re.compile(r"^\| `([a-z_.<>]+)` \| ([^|]+) \|")
#: The shipped entry each ``<key>`` of a documented path is tried on (the boat: its depth range
#: [0, 0] leaves both depth bounds reachable).
EXAMPLE_KEY = {"sonars": "edgetech_2205", "platforms": "boat", "envelopes": "auv", "noise": "auv"}


def _documented() -> dict[str, str]:
    text = (REPO / "data" / "README.md").read_text(encoding="utf-8")
    section = text.split("## Valid values", 1)[1].split("\n## ", 1)[0]  # the area file's table is its own
    return {m.group(1): m.group(2).strip() for m in map(ROW.match, section.splitlines()) if m}


def _model_paths(cls=models.Data, prefix="") -> set[str]:
    """Dotted paths of every sourced value of the model (``<key>`` for a dict's keys)."""
    out = set()
    for name, field in cls.model_fields.items():
        ann = field.annotation
        if get_origin(ann) in (Union, types.UnionType):
            ann = next(a for a in get_args(ann) if a is not type(None))
        path = f"{prefix}{name}"
        if get_origin(ann) is dict:
            ann, path = get_args(ann)[1], f"{path}.<key>"
        if isinstance(ann, type) and issubclass(ann, Sourced):
            out.add(path)
        elif isinstance(ann, type) and issubclass(ann, BaseModel):
            out |= _model_paths(ann, f"{path}.")
    return out


def _concrete(path: str) -> list[str]:
    parts = path.split(".")
    parts[1] = EXAMPLE_KEY.get(parts[0], parts[1]) if parts[1] == "<key>" else parts[1]
    return [("port" if p == "<side>" else p) for p in parts]


def _with_value(parts: list[str], value) -> dict:
    doc = copy.deepcopy(datadoc.shipped_document())
    node = doc
    for part in parts[:-1]:
        node = node.setdefault(part, {})  # an optional table the entry lacks
    node[parts[-1]] = {"value": value, "assumption": "test"}
    return doc


def _error(doc) -> str | None:
    try:
        models.validate_document(doc)
    except ValueError as exc:
        return str(exc)
    return None


def test_every_sourced_value_is_documented_with_its_range():
    documented = {p.replace("<side>", s) for p in _documented() for s in ("port", "starboard")}
    assert _model_paths() == documented


def _bounds(rule: str):
    m = re.fullmatch(r"([\[(])(-?[\d.∞]+|-∞), (-?[\d.∞]+)([\])])", rule)
    if not m:
        return None
    lo = -math.inf if m.group(2) in ("-∞", "∞") else float(m.group(2))
    hi = math.inf if m.group(3) == "∞" else float(m.group(3))
    return lo, m.group(1) == "[", hi, m.group(4) == "]"


NUMBER_ROWS = [(p, r) for p, r in _documented().items() if _bounds(r)]


@pytest.mark.parametrize("path, rule", NUMBER_ROWS, ids=[p for p, _ in NUMBER_ROWS])
def test_each_documented_bound_refuses_just_outside_and_accepts_on_it(path, rule):
    lo, lo_closed, hi, hi_closed = _bounds(rule)
    parts = _concrete(path)
    where = ".".join(parts) + ".value"
    for end, closed, outward in ((lo, lo_closed, -math.inf), (hi, hi_closed, math.inf)):
        if math.isinf(end):
            message = _error(_with_value(parts, end))  # infinity is not a finite number
            assert message and message.startswith(where) and "finite number" in message
            continue
        outside = math.nextafter(end, outward) if closed else end
        message = _error(_with_value(parts, outside))
        assert message is not None, f"{where} = {outside!r} accepted, documented {rule}"
        assert message.startswith(f"{where} must be a finite number in ") and repr(outside) in message
        shown = re.search(r"in ([\[(])(\S+), (\S+)([\])]);", message)
        assert shown and (float(shown.group(2)), float(shown.group(3))) == (lo, hi), message
        if closed:
            inside = _error(_with_value(parts, end))
            assert inside is None or where not in inside, inside  # another rule (an order) may object


def test_choices_and_booleans_refuse_anything_else():
    documented = _documented()
    assert documented["platforms.<key>.azimuth_positive"] == "`down` or `up`"
    for value in ("down", "up"):
        assert _error(_with_value(_concrete("platforms.<key>.azimuth_positive"), value)) is None
    message = _error(_with_value(_concrete("platforms.<key>.azimuth_positive"), "sideways"))
    assert message == "platforms.boat.azimuth_positive.value must be one of ['down', 'up']; got 'sideways'"
    assert documented["envelopes.<key>.same_altitude"] == "`true` or `false`"
    for value, ok in ((True, True), (False, True), (1, False), ("true", False)):
        message = _error(_with_value(_concrete("envelopes.<key>.same_altitude"), value))
        assert (message is None) == ok, message


@pytest.mark.parametrize("value", [True, "15", float("nan"), [15.0]])
def test_a_number_is_never_coerced(value):
    message = _error(_with_value(_concrete("platforms.<key>.transducers.<side>.tilt_deg"), value))
    assert message == (f"platforms.boat.transducers.port.tilt_deg.value must be a finite number in "
                       f"[-90.0, 90.0]; got {value!r}")


@pytest.mark.parametrize("entry, found", [
    ({"value": 1.0}, "none"),
    ({"value": 1.0, "source": "a", "assumption": "b"}, "['source', 'assumption']"),
])
def test_exactly_one_of_source_and_assumption(entry, found):
    doc = copy.deepcopy(datadoc.shipped_document())
    doc["survey"]["margin_m"] = entry
    assert _error(doc) == f"survey.margin_m needs exactly one of 'source' or 'assumption'; found {found}"
    doc["survey"]["margin_m"] = {"value": 1.0, "source": "  "}
    assert _error(doc) == "survey.margin_m.source must be a non-empty string; got '  '"


def test_every_shipped_file_and_example_validates():
    for path in sorted((REPO / "data").glob("*.toml")):
        models.validate_document(read_toml(path))  # each file alone
    for example in ("my_auv.toml", "my_blueboat.toml"):
        data = models.validate_document(datadoc.document(userdata.make_inputs([REPO / "data" / "examples" / example])),
                                        datadoc.USER_TABLES)
        assert example.removesuffix(".toml") in data.platforms


def test_unknown_keys_suggest_the_key_meant_at_any_depth():
    doc = copy.deepcopy(datadoc.shipped_document())
    doc["platforms"]["auv"]["atitude"] = doc["platforms"]["auv"].pop("attitude")
    assert _error(doc) == ("platforms.auv.atitude: unknown key 'atitude'; did you mean `attitude`? (keys here: "
                           "attitude, azimuth_positive, depth_m, length_m, mission, name, reference_point, sonar, "
                           "survey, transducers)")
    doc = copy.deepcopy(datadoc.shipped_document())
    doc["noise"]["auv"]["xyz"] = {"value": 1.0, "source": "x"}
    assert _error(doc).startswith("noise.auv.xyz: unknown key 'xyz' (keys here: ")  # nothing close: no guess


def test_a_typo_in_a_users_file_names_the_file_the_key_and_the_key_meant(tmp_path):
    user = tmp_path / "mine.toml"
    user.write_text('[platforms.auv.atitude]\npitch_max_deg = { value = 20.0, assumption = "ours" }\n')
    with pytest.raises(ValueError) as info:
        userdata.use([user])
    message = str(info.value)
    assert message.startswith("platforms.auv.atitude: unknown key 'atitude'; did you mean `attitude`?")
    assert message.endswith(f"(from data file {user})") and "\n" not in message
    assert userdata.active().is_default


def test_the_validated_values_are_the_files_values():
    data = models.validate_document(datadoc.shipped_document(), datadoc.USER_TABLES)
    raw = read_toml(REPO / "data" / "platforms.toml")
    tilt = data.platforms["auv"].transducers.starboard.tilt_deg
    assert tilt.value == raw["platforms"]["auv"]["transducers"]["starboard"]["tilt_deg"]["value"]
    assert tilt.note == "source: " + raw["platforms"]["auv"]["transducers"]["starboard"]["tilt_deg"]["source"]
    with pytest.raises(Exception):
        data.platforms["auv"].name = "x"  # frozen


def test_the_survey_design_table_is_checked_before_any_work():
    # before the data model, a bad survey_design value passed the preflight and failed inside the
    # survey-design notebook; a share above 1 is not a share
    with pytest.raises(ValueError) as info:
        userdata.use([], ["survey_design.min_two_view_share=1.5"])
    assert str(info.value) == ("survey_design.min_two_view_share.value must be a finite number in [0.0, 1.0]; "
                               "got 1.5 (set by --set survey_design.min_two_view_share=1.5)")
    assert userdata.active().is_default


@pytest.mark.parametrize("table", ["survey", "mission"])
def test_an_optional_table_given_as_a_number_is_refused_in_one_line(table, tmp_path):
    # before the data model this was a TypeError with a traceback ("argument of type 'int' ...")
    user = tmp_path / "mine.toml"
    user.write_text(f"[platforms.auv]\n{table} = 3\n")
    with pytest.raises(ValueError) as info:
        userdata.use([user])
    assert str(info.value) == f"platforms.auv.{table} must be a table; got int (from data file {user})"
