"""Nothing wrong accepted (issue 27, items 4-6 and 9): a misspelt data key, impossible hardware
and bad notebook parameters are refused before any work, in one line naming the key or
parameter, the value and the rule; possible-but-suspicious values are flagged.

The expected rules are physics and the schema of ``data/*.toml``, not the code's output: a
transducer 45 m above the sea cannot image the seafloor, an envelope cannot pitch beyond its
vehicle, a seafloor beyond the sonar's range is never seen.
"""

from __future__ import annotations

import math

import pytest

from sss_locus.experiments.datamodel import userdata
from sss_locus.pipeline.cli import command as cli
from sss_locus.pipeline.run.registry import ParameterError, get_entry


def _refused(sets=(), files=()):
    with pytest.raises(ValueError) as info:
        userdata.use(list(files), list(sets))
    message = str(info.value)
    assert "\n" not in message
    return message


# -- item 4: unknown keys, with the nearest known key ------------------------------------------

@pytest.mark.parametrize("key, typo, meant", [
    ("platforms.auv.transducers.port", "tilt_dge", "tilt_deg"),
    ("platforms.auv.attitude", "pich_max_deg", "pitch_max_deg"),
    ("sonars.edgetech_2205", "max_rnage_m", "max_range_m"),
    ("envelopes.auv", "altitude_mx_m", "altitude_max_m"),
])
def test_a_misspelt_data_key_is_refused_with_the_key_meant(key, typo, meant):
    message = _refused([f"{key}.{typo}=45"])
    assert f"{key}.{typo}" in message and f"did you mean `{meant}`?" in message
    assert "set by --set" in message


def test_a_misspelt_key_in_a_data_file_is_refused_naming_the_file(tmp_path):
    user = tmp_path / "mine.toml"
    user.write_text('[platforms.auv.transducers.port.tilt_dge]\nvalue = 45.0\nassumption = "x"\n')
    message = _refused(files=[user])
    assert "did you mean `tilt_deg`?" in message and str(user) in message


def test_a_byte_order_mark_and_a_directory_are_named_as_such(tmp_path):
    user = tmp_path / "bom.toml"
    user.write_bytes(b'\xef\xbb\xbf[platforms.auv.transducers.port.tilt_deg]\nvalue = 15.0\nassumption = "x"\n')
    doc = userdata.validate(userdata.make_inputs([user]))
    assert doc["platforms"]["auv"]["transducers"]["port"]["tilt_deg"]["value"] == 15.0
    assert "is a directory, not a TOML file" in _refused(files=[tmp_path])


def test_the_example_data_file_passes_every_check():
    inputs = userdata.use(["data/examples/my_auv.toml"])
    assert userdata.hardware_flags(inputs) == []
    userdata.use()


# -- item 5: impossible hardware ---------------------------------------------------------------

@pytest.mark.parametrize("override, fragments", [
    # the AUV's shallowest depth is 2 m: a transducer 47 m above its hull axis is 45 m in the air
    ("platforms.auv.transducers.port.depth_m=-47", ["45 m above the sea surface", "depth_m = -47"]),
    ("platforms.boat.transducers.starboard.depth_m=-0.5", ["0.5 m above the sea surface"]),
    ("envelopes.auv.pitch_max_deg=60", ["exceeds the vehicle's limit", "pitch_max_deg = 45"]),
    ("envelopes.auv.altitude_max_m=150", ["beyond the sonar's range", "max_range_m = 150"]),
    ('platforms.auv.name="AUV \U0001F680"', ["use text the figures can draw"]),
])
def test_impossible_hardware_is_refused_with_the_rule_and_the_value(override, fragments):
    message = _refused([override])
    for fragment in fragments:
        assert fragment in message, message
    assert "rule" in message or "draw" in message


def test_apertures_in_radians_are_refused_and_a_tilt_in_radians_is_flagged():
    edgetech = (math.radians(130.0), math.radians(0.27))
    message = _refused([f"sonars.edgetech_2205.azimuth_deg={edgetech[0]}",
                        f"sonars.edgetech_2205.elevation_deg={edgetech[1]}"])
    assert "look like radians" in message and "130 x 0.27 deg" in message
    tilted = userdata.make_inputs([], [f"platforms.auv.transducers.port.tilt_deg={math.radians(25.5)}"])
    userdata.validate(tilted)  # possible: a nearly horizontal transducer
    flags = userdata.hardware_flags(tilted)
    assert len(flags) == 1 and "tilt_deg" in flags[0] and "25.5 deg" in flags[0]


def test_a_range_in_millimetres_is_flagged_against_the_survey_altitude():
    # a 40 m range written as 40000 (mm) with a 2-6 m survey altitude passed silently
    mm = userdata.make_inputs([], ["sonars.edgetech_2205.max_range_m=150000"])
    userdata.validate(mm)  # flagged, not refused
    flags = userdata.hardware_flags(mm)
    assert len(flags) == 1 and "envelopes.auv.altitude_max_m = 30 m is 0.02 %" in flags[0], flags
    assert "max_range_m = 150000 m" in flags[0] and "mm or cm" in flags[0]
    assert userdata.hardware_flags(userdata.make_inputs([], ["sonars.edgetech_2205.max_range_m=2999"])) == []


def test_a_beam_alone_in_radians_beside_a_fan_in_degrees_is_flagged():
    # a 60 deg x 0.25 deg sonar written with the beam in radians (0.0044) passed silently
    beam = userdata.make_inputs([], [f"sonars.edgetech_2205.elevation_deg={math.radians(0.27)}"])
    userdata.validate(beam)  # flagged, not refused
    flags = userdata.hardware_flags(beam)
    assert len(flags) == 1 and "sonars.edgetech_2205.elevation_deg" in flags[0] and "0.27 deg beam" in flags[0], flags
    assert userdata.hardware_flags(userdata.make_inputs([], ["sonars.edgetech_2205.elevation_deg=0.1"])) == []


def test_the_command_refuses_a_typo_before_any_notebook(tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("SSS_LOCUS_BUILD_DIR", str(tmp_path / "build"))
    code = cli.main(["run", "concept", "--set", "platforms.auv.transducers.port.tilt_dge=45"])
    err = capsys.readouterr().err
    assert code == 2 and "did you mean `tilt_deg`?" in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "build").exists()
    userdata.use()


# -- item 6: every declared parameter checked before work ---------------------------------------

@pytest.mark.parametrize("notebook, name, text, fragment", [
    ("derivation", "seed", "4294967296", "out of range"),
    ("pose_space", "check_seed", "-1", "out of range"),
    ("concept", "platforms", "[]", "is empty"),
    ("noise", "noise_scales", "[]", "is empty"),
    ("rigs", "plot_range_m", "[]", "is empty"),
    ("survey_passes", "paper_band_deg", "[10.0]", "has 1 value(s)"),
    ("noise", "noise_scales", "[1e300]", "out of range"),
    ("concept", "feature_x_m", "1e999", "must be a finite number"),
    ("concept", "feature_x_m", "1e6", "out of range"),
    ("water", "surface_tilts_deg", "[1e999]", "must be a finite number"),
])
def test_bad_parameters_are_refused_by_name_before_work(notebook, name, text, fragment):
    entry = get_entry(notebook)
    with pytest.raises(ParameterError) as info:
        entry.resolve("quick", {name: text}, from_text=True)
    message = str(info.value)
    assert f"parameter '{name}" in message and fragment in message and "\n" not in message
