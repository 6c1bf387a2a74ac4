"""A user's own sonar and vehicle (sss_locus.experiments.datamodel.userdata, ``--data``/``--set``) and the
frames API (``Transducer.world_pose``)."""

from __future__ import annotations

import math
import shutil

import numpy as np
import pytest

from sss_locus import relative_pose, two_view_locus
from sss_locus.experiments.datamodel import userdata
from sss_locus.experiments.datamodel.envelopes import load_envelope
from sss_locus.experiments.datamodel.platforms import load_platform, load_platforms
from sss_locus.experiments.passes.straight_pass import observe_pass
from sss_locus.paths import REPO_ROOT

EXAMPLE = REPO_ROOT / "data" / "examples" / "my_auv.toml"


@pytest.fixture(autouse=True)
def _default_data():
    yield
    userdata.use()  # leave the process with the shipped data only


def test_example_file_adds_a_platform_with_an_underscore_key():
    userdata.use([EXAMPLE])
    platforms = load_platforms()
    assert list(platforms)[:2] == ["boat", "auv"] and "my_auv" in platforms  # shipped order kept
    mine = platforms["my_auv"]
    assert (mine.sonar.azimuth_deg, mine.sonar.elevation_deg, mine.sonar.max_range_m) == (40.0, 0.2, 100.0)
    assert {t.tilt_deg for t in mine.transducers.values()} == {15.0}
    assert load_envelope("my_auv").altitude_max_m == 20.0
    assert userdata.label_key("my_auv") == "my-auv"


def test_partial_override_replaces_one_value_with_its_own_provenance(tmp_path):
    user = tmp_path / "tilt.toml"
    user.write_text('[platforms.auv.transducers.port.tilt_deg]\nvalue = 15.0\nassumption = "ours"\n')
    userdata.use([user])
    auv = load_platform("auv")
    assert auv.transducers["port"].tilt_deg == 15.0
    assert auv.transducers["starboard"].tilt_deg == 25.5  # untouched
    assert auv.provenance["platforms.auv.transducers.port.tilt_deg"] == "assumption: ours"
    assert auv.sonar.name.startswith("EdgeTech")


def test_set_override_is_recorded_as_a_user_override():
    userdata.use([], ["platforms.boat.transducers.port.tilt_deg=35"])
    boat = load_platform("boat")
    assert boat.transducers["port"].tilt_deg == 35.0
    assert boat.provenance["platforms.boat.transducers.port.tilt_deg"].startswith(
        "assumption: user override: --set platforms.boat")
    record = userdata.record(["boat"])
    assert record["overrides"] == ["platforms.boat.transducers.port.tilt_deg=35"]
    assert record["values"]["boat"]["set_by_user"] == ["platforms.boat.transducers.port.tilt_deg"]


@pytest.mark.parametrize("text, match", [
    ('[platforms.auv.transducers.port]\ntilt_deg = { value = 120.0, source = "x" }\n',
     r"platforms\.auv\.transducers\.port\.tilt_deg\.value must be a finite number in \[-90\.0, 90\.0\]"),
    ('[platforms.auv.transducers.port]\ntilt_deg = { value = 12.0 }\n',
     r"platforms\.auv\.transducers\.port\.tilt_deg needs exactly one of 'source' or 'assumption'"),
    ('[platforms.My-AUV]\nname = "x"\n', r"platforms\.My-AUV: keys must match"),
    ('[vehicles.x]\nname = "x"\n', r"unknown top-level keys \['vehicles'\]"),
    ('[platforms.new_auv]\nname = "x"\nsonar = "nope"\n', r"platforms\.new_auv\.sonar names unknown sonar 'nope'"),
])
def test_bad_user_files_name_the_key_path(tmp_path, text, match):
    user = tmp_path / "bad.toml"
    user.write_text(text)
    with pytest.raises(ValueError, match=match) as info:
        userdata.use([user])
    assert userdata.active().is_default  # a rejected file never becomes active
    assert str(user) in str(info.value)  # and the file that holds it


def test_the_message_names_which_of_several_inputs_holds_the_bad_entry(tmp_path):
    good, bad = tmp_path / "good.toml", tmp_path / "bad.toml"
    good.write_text('[platforms.auv.transducers.port]\ntilt_deg = { value = 12.0, source = "x" }\n')
    bad.write_text('[platforms.boat.transducers.port]\ntilt_deg = { value = 120.0, source = "x" }\n')
    with pytest.raises(ValueError, match=f"\\(from data file {bad}\\)$"):
        userdata.use([bad, good])
    with pytest.raises(ValueError, match=r"\(set by --set platforms\.auv\.transducers\.port\.tilt_deg=95\)$"):
        userdata.use([good], ["platforms.auv.transducers.port.tilt_deg=95"])


def test_cli_rejects_bad_data_before_any_notebook(tmp_path, monkeypatch, capsys):
    from sss_locus.pipeline.cli import command as cli

    monkeypatch.setenv("SSS_LOCUS_BUILD_DIR", str(tmp_path / "build"))
    code = cli.main(["run", "pose_space", "--set", "platforms.auv.transducers.port.tilt_deg=95"])
    assert code == 2
    assert "platforms.auv.transducers.port.tilt_deg.value must be a finite number" in capsys.readouterr().err
    assert not (tmp_path / "build").exists()
    code = cli.main(["run", "pose_space", "-p", "platforms", '["my_auv"]'])
    assert code == 2 and "'my_auv' is not allowed" in capsys.readouterr().err  # not in the shipped data


def test_platform_choices_follow_the_data():
    from sss_locus.pipeline.run.registry import get_entry

    entry = get_entry("pose_space")
    with pytest.raises(ValueError, match="one of 'boat', 'auv'"):
        entry.resolve("quick", {"platforms": ["my_auv"]})
    userdata.use([EXAMPLE])
    assert entry.resolve("quick", {"platforms": ["my_auv"]})["platforms"] == ["my_auv"]


def test_run_key_holds_the_data_file_paths_not_their_bytes(tmp_path):
    """Editing a user file does not change any run key: the entries each run read are checked
    one by one instead (test_user_platform_runs_through_the_platform_notebooks)."""
    from sss_locus.pipeline.run.outputs import data_read_changed, run_key
    from sss_locus.pipeline.run.registry import load_registry
    from sss_locus.pipeline.run.runner import resolve_parameters

    user = tmp_path / "my_auv.toml"
    shutil.copy(EXAMPLE, user)
    data = userdata.use([user])
    entries = load_registry()

    def keys():
        return {name: run_key(e, "quick", resolve_parameters(e, "quick", data=data)) for name, e in entries.items()}

    before = keys()
    record = {"parameters": {"data_files": [str(user)]},
              "data_read": userdata.datadoc.entries_sha256(["noise.my_auv", "platforms.my_auv"], data)}
    assert not data_read_changed(record)
    user.write_text(user.read_text().replace("roll_sigma_deg = { value = 0.1", "roll_sigma_deg = { value = 0.2"))
    assert keys() == before
    assert data_read_changed(record)
    assert not data_read_changed({**record, "data_read": {k: v for k, v in record["data_read"].items()
                                                          if k == "platforms.my_auv"}})
    user.unlink()
    assert data_read_changed(record)  # unreadable inputs are stale, never silently fresh


def _sensor_pose_by_hand(transducer, position, yaw, pitch, roll):
    """Independent composition from data/README.md's statement of the frames."""
    def rz(a):
        c, s = math.cos(a), math.sin(a)
        return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])

    def ry(a):
        c, s = math.cos(a), math.sin(a)
        return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])

    def rx(a):
        c, s = math.cos(a), math.sin(a)
        return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])

    Rv = rz(math.radians(yaw)) @ ry(-math.radians(pitch)) @ rx(math.radians(roll))
    side = 1.0 if transducer.side == "port" else -1.0
    tau = math.radians(transducer.tilt_deg)
    x = np.array([0.0, side * math.cos(tau), -math.sin(tau)])
    y = np.array([0.0, -side * math.sin(tau), -math.cos(tau)])
    M = np.column_stack([x, y, np.cross(x, y)])
    m = np.array([transducer.forward_offset_m, side * transducer.lateral_offset_m, -transducer.depth_m])
    return Rv @ M, np.asarray(position) + Rv @ m


def test_world_pose_matches_the_frames_statement_and_is_batched():
    userdata.use([EXAMPLE])
    t = load_platform("my_auv").transducers["starboard"]
    rng = np.random.default_rng(3)
    pos = rng.normal(size=(5, 3)) * 10
    yaw, pitch, roll = rng.uniform(-180, 180, 5), rng.uniform(-30, 30, 5), rng.uniform(-10, 10, 5)
    W, o = t.world_pose(pos, yaw, pitch, roll)
    assert W.shape == (5, 3, 3) and o.shape == (5, 3)
    for i in range(5):
        W_ref, o_ref = _sensor_pose_by_hand(t, pos[i], yaw[i], pitch[i], roll[i])
        np.testing.assert_allclose(W[i], W_ref, atol=1e-12)
        np.testing.assert_allclose(o[i], o_ref, atol=1e-12)
    with pytest.raises(ValueError, match="position_m"):
        t.world_pose([0.0, 1.0], 0, 0, 0)


def test_world_pose_and_relative_pose_reproduce_observe_pass_and_the_locus():
    """Two passes of observe_pass (feature at the world origin); the sensors' poses from
    world_pose give the same feature coordinates, and the two-view locus passes through it."""
    pf = load_platform("auv")
    heading, pitch = np.array([0.0, 35.0]), np.array([5.0, -8.0])
    obs = observe_pass(pf, np.array([True, True]), heading, np.array([20.0, 24.0]), np.array([15.0, 12.0]),
                       pitch, np.array([0.0005, -0.0008]))
    assert np.all(obs["reason"] == -1)
    t = pf.transducers["port"]
    h = np.radians(heading)
    # vehicle reference point at the ping: along-track s, the feature at ground offset g to port
    e = np.stack([np.cos(h), np.sin(h), 0 * h], -1)
    n = np.stack([-np.sin(h), np.cos(h), 0 * h], -1)
    vehicle = obs["s"][:, None] * e - np.array([20.0, 24.0])[:, None] * n + np.array([15.0, 12.0])[:, None] * [0, 0, 1]
    W, origin = t.world_pose(vehicle, heading, pitch, 0.0)
    np.testing.assert_allclose(W, obs["W"], atol=1e-12)
    np.testing.assert_allclose(origin, obs["origin"], atol=1e-9)
    R, tt = relative_pose(W[0], origin[0], W[1], origin[1])
    p1, p2 = obs["p"]
    np.testing.assert_allclose(R @ p1 + tt, p2, atol=1e-9)
    ap = pf.sonar.aperture()
    locus = two_view_locus(R, tt, np.linalg.norm(p1), np.linalg.norm(p2), ap, ap)
    assert float(locus.length) > 0
    # the feature lies on the locus circle: distance to the centre equals the radius, in its plane
    c, nrm, rad = np.asarray(locus.center), np.asarray(locus.normal), float(locus.radius)
    assert abs(float(np.dot(p1 - c, nrm))) < 1e-6 and abs(np.linalg.norm(p1 - c) - rad) < 1e-6


def test_terrain_and_survey_are_overridden_by_key_and_validated(tmp_path):
    from sss_locus.experiments.datamodel.terrain import load_terrain_config

    shipped = load_terrain_config()
    user = tmp_path / "seafloor.toml"
    user.write_text('[terrain.random.rms_relief_m]\nvalue = 2.5\nassumption = "our multibeam survey"\n'
                    '[survey.line_spacing_m]\nvalue = 80.0\nsource = "our survey plan"\n')
    userdata.use([user], ["terrain.slope.slope_deg=7", "survey.area_m=400"])
    cfg = load_terrain_config()
    assert cfg["random"]["rms_relief_m"] == 2.5 and cfg["survey"]["line_spacing_m"] == 80.0
    assert cfg["slope"]["slope_deg"] == 7.0 and cfg["survey"]["area_m"] == 400.0
    assert cfg["random"]["correlation_length_m"] == shipped["random"]["correlation_length_m"]  # untouched
    assert cfg["provenance"]["terrain.random.rms_relief_m"] == "assumption: our multibeam survey"
    assert cfg["provenance"]["survey.area_m"] == "assumption: user override: --set survey.area_m=400"
    # only a run that reads the shared tables counts them as changed
    assert userdata.changed_from_shipped(["auv"], userdata.active()) == []
    assert userdata.changed_from_shipped(["auv"], userdata.active(), ["terrain", "survey"]) == [
        "terrain.random.rms_relief_m", "terrain.slope.slope_deg", "survey.area_m", "survey.line_spacing_m"]


@pytest.mark.parametrize("text, sets, match", [
    ('[terrain.random]\nrms_relief_m = { value = -1.0, assumption = "x" }\n', [],
     r"terrain\.random\.rms_relief_m\.value must be a finite number in \[0\.0, 1000\.0\]; got -1\.0 \(from data file "),
    ('[terrain.hills]\nheight_m = { value = 1.0, assumption = "x" }\n', [],
     r"terrain\.hills: unknown key 'hills' \(keys here: mound, random, slope, step\) \(from data file "),
    ('[survey]\nlanes_m = { value = 1.0, assumption = "x" }\n', [], r"survey\.lanes_m: unknown key 'lanes_m'.*\(from data file "),
    ("", ["survey.bogus_m=5"], r"survey\.bogus_m: unknown key 'bogus_m'.*\(set by --set survey\.bogus_m=5\)"),
    ("", ["survey.margin_m=-5"], r"survey\.margin_m\.value must be .*\(set by --set survey\.margin_m=-5\)"),
])
def test_bad_terrain_input_names_the_key_and_where_it_came_from(tmp_path, text, sets, match):
    user = tmp_path / "bad.toml"
    user.write_text(text)
    with pytest.raises(ValueError, match=match):
        userdata.use([user], sets)
    assert userdata.active().is_default


# -- a data directory (--data-dir DIR, $SSS_LOCUS_DATA_DIR) -----------------------------------------

def _azimuth(value: float) -> str:
    return f'[sonars.edgetech_2205.azimuth_deg]\nvalue = {value}\nassumption = "test"\n'


def test_a_data_directory_is_its_toml_files_in_name_order_before_the_data_files(tmp_path, monkeypatch, capsys):
    """Each DIR/*.toml is read as a --data file, by name, before the --data files (later ones win);
    hidden files, sub-folders and other files are not read (each would be refused if it were)."""
    from sss_locus.pipeline.cli import command as cli

    monkeypatch.setenv("SSS_LOCUS_BUILD_DIR", str(tmp_path / "build"))
    mine = tmp_path / "mine"
    (mine / "sub").mkdir(parents=True)
    (mine / "b.toml").write_text(_azimuth(110.0))
    (mine / "a.toml").write_text(_azimuth(100.0))
    for bad in (mine / ".a.toml", mine / "sub" / "c.toml", mine / "notes.txt"):
        bad.write_text("not = [valid")
    last = tmp_path / "z.toml"
    last.write_text(_azimuth(120.0))
    shipped = userdata.document()["sonars"]["edgetech_2205"]["azimuth_deg"]["value"]
    for argv, files, value in ((["--data-dir", str(mine)], ["a.toml", "b.toml"], 110.0),
                               (["--data-dir", str(mine), "--data", str(last)], ["a.toml", "b.toml", "z.toml"], 120.0)):
        code = cli.main(["run", "concept", "--profile", "quick", *argv])  # refused: a user run needs --name
        err = capsys.readouterr().err
        assert code == 2 and f"reads data file(s) {', '.join(files)}," in err, err
        assert [p.rsplit("/", 1)[1] for p in userdata.active().files] == files
        assert userdata.document()["sonars"]["edgetech_2205"]["azimuth_deg"]["value"] == value != shipped
    monkeypatch.setenv("SSS_LOCUS_DATA_DIR", str(mine))  # the same from the environment
    assert cli.main(["run", "concept", "--profile", "quick"]) == 2
    assert "reads data file(s) a.toml, b.toml," in capsys.readouterr().err
    assert not (tmp_path / "build").exists()


@pytest.mark.parametrize("kind", ["missing", "file", "empty", "from-environment"])
def test_a_bad_data_directory_is_refused_in_one_line_naming_it(tmp_path, monkeypatch, capsys, kind):
    from sss_locus.pipeline.cli import command as cli

    monkeypatch.setenv("SSS_LOCUS_BUILD_DIR", str(tmp_path / "build"))
    folder = tmp_path / "mine"
    if kind == "file":
        folder.write_text(_azimuth(100.0))
    elif kind in ("empty", "from-environment"):
        (folder / "sub").mkdir(parents=True)
        (folder / "sub" / "a.toml").write_text(_azimuth(100.0))  # sub-folders are not read
        (folder / "README.md").write_text("my data")
    argv = ["run", "concept", "--profile", "quick"]
    if kind == "from-environment":
        monkeypatch.setenv("SSS_LOCUS_DATA_DIR", str(folder))
    else:
        argv += ["--data-dir", str(folder)]
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and str(folder) in err, err
    said = {"missing": "does not exist", "file": "is not a folder", "empty": "holds no .toml file",
            "from-environment": "holds no .toml file"}[kind]
    assert said in err and ("SSS_LOCUS_DATA_DIR" if kind == "from-environment" else "--data-dir") in err
    assert not (tmp_path / "build").exists()


SHIPPED_SONAR = "EdgeTech 2205 (approximation, as in the paper)"
SHIPPED_AUV = "Torpedo AUV (REMUS-100 / Iver3 class), dual EdgeTech 2205"


def test_a_shipped_sonar_with_other_values_is_not_named_as_shipped(tmp_path):
    # a user's file gives the EdgeTech 2205 entry a 100 deg aperture and keeps its name: every
    # figure title and caption would otherwise name the shipped sonar for a fan it does not have
    user = tmp_path / "sonar.toml"
    user.write_text('[sonars.edgetech_2205.azimuth_deg]\nvalue = 100.0\nassumption = "ours"\n')
    userdata.use([user])
    auv = load_platform("auv")
    assert auv.sonar.azimuth_deg == 100.0
    assert auv.sonar.name == f"{SHIPPED_SONAR} (changed: azimuth_deg)"
    assert auv.name == f"{SHIPPED_AUV} (changed: sonar azimuth_deg)"
    assert "(changed: azimuth_deg), 100° × 0.27°" in userdata.describe_platform("auv")
    assert load_platform("boat").name == "Surface boat (BlueBoat-class), dual Omniscan 450 SS"  # other sonar
    # the change is listed once, as the value it is, not again as a change of name
    assert userdata.changed_from_shipped(["auv"]) == ["sonars.edgetech_2205.azimuth_deg"]


def test_a_platform_value_set_on_the_command_line_marks_that_platform_only():
    userdata.use([], ["platforms.boat.transducers.port.tilt_deg=35"])
    assert load_platform("boat").name.endswith("(changed: transducers.port.tilt_deg)")
    assert load_platform("boat").sonar.name == "Cerulean Omniscan 450 SS"  # the sonar is as shipped
    assert load_platform("auv").name == SHIPPED_AUV


def test_a_new_source_for_the_shipped_value_or_a_new_name_is_not_marked(tmp_path):
    same = tmp_path / "same.toml"
    same.write_text('[sonars.edgetech_2205.azimuth_deg]\nvalue = 130.0\nsource = "our own datasheet"\n')
    userdata.use([same])
    assert load_platform("auv").sonar.name == SHIPPED_SONAR and load_platform("auv").name == SHIPPED_AUV
    renamed = tmp_path / "renamed.toml"
    renamed.write_text('[sonars.edgetech_2205]\nname = "Our 2205, wide"\n'
                       'azimuth_deg = { value = 100.0, assumption = "ours" }\n')
    userdata.use([renamed])
    assert load_platform("auv").sonar.name == "Our 2205, wide"
    assert load_platform("auv").name == f"{SHIPPED_AUV} (changed: sonar azimuth_deg)"
    assert userdata.changed_from_shipped(["auv"]) == ["sonars.edgetech_2205.azimuth_deg", "sonars.edgetech_2205.name"]


def _example_without(tmp_path, *sections):
    """The worked example with its ``[<section>.my_auv]`` tables cut out."""
    kept, skipping = [], False
    for line in EXAMPLE.read_text().splitlines():
        if line.startswith("["):
            skipping = any(line.startswith(f"[{s}.my_auv") for s in sections)
        if not skipping:
            kept.append(line)
    path = tmp_path / f"no_{'_'.join(sections)}.toml"
    path.write_text("\n".join(kept) + "\n")
    return path


def test_a_platform_without_its_noise_or_envelope_table_is_named_with_the_missing_table(tmp_path):
    from sss_locus.experiments.datamodel.noise_model import load_noise_model
    from sss_locus.experiments.passes.pass_noise import load_pass_noise

    userdata.use([_example_without(tmp_path, "noise", "envelopes")])
    assert "my_auv" in load_platforms()  # the platform itself is there
    for load, table, schema in ((load_pass_noise, "noise", "noise.toml"), (load_noise_model, "noise", "noise.toml"),
                                (load_envelope, "envelopes", "survey.toml")):
        with pytest.raises(ValueError) as info:
            load("my_auv")
        message = str(info.value)  # not "platform_key must be one of ['auv', 'boat']" of a key that exists
        assert f"no [{table}.my_auv] table" in message and f"data/{schema}" in message, message
        assert "'auv'" in message and "'boat'" in message


def test_a_chapter_that_reads_a_missing_table_refuses_the_platform_before_it_runs(tmp_path, monkeypatch, capsys):
    from sss_locus.pipeline.cli import command as cli
    from sss_locus.pipeline.run.registry import get_entry

    data = _example_without(tmp_path, "noise")  # platform and envelope, no noise model
    userdata.use([data])
    assert get_entry("pose_space").resolve("quick", {"platforms": ["my_auv"]})["platforms"] == ["my_auv"]
    assert get_entry("planning").resolve("quick", {"platforms": ["my_auv"]})["platforms"] == ["my_auv"]
    for chapter in ("survey_design", "noise", "three_views", "reconstruction"):  # they read [noise.my_auv]
        with pytest.raises(ValueError, match=r"no \[noise\.my_auv\] table .*data/noise\.toml"):
            get_entry(chapter).resolve("quick", {"platforms": ["my_auv"]})
    userdata.use([_example_without(tmp_path, "envelopes")])
    for chapter in ("planning", "survey_passes", "water", "noise"):  # they read [envelopes.my_auv]
        with pytest.raises(ValueError, match=r"no \[envelopes\.my_auv\] table .*data/survey\.toml"):
            get_entry(chapter).resolve("quick", {"platforms": ["my_auv"]})
    userdata.use()
    monkeypatch.setenv("SSS_LOCUS_BUILD_DIR", str(tmp_path / "build"))
    code = cli.main(["run", "survey_design", "--data", str(data), "-p", "platforms", '["my_auv"]', "--name", "mine"])
    assert code == 2 and "no [noise.my_auv] table" in capsys.readouterr().err  # not 47 s into cell 3
    assert not (tmp_path / "build").exists()


def test_a_users_own_platform_changed_on_the_command_line_is_not_named_as_their_file_has_it(tmp_path):
    # the user's own name says "20° tilt"; a --set of 30° must not leave a figure title saying 20°
    user = tmp_path / "rov.toml"
    text = EXAMPLE.read_text()
    user.write_text(text)
    userdata.use([user], ["platforms.my_auv.transducers.port.tilt_deg=30"])
    shipped_name = load_platforms()["my_auv"].name  # marked
    userdata.use([user])
    assert load_platform("my_auv").name + " (changed: transducers.port.tilt_deg)" == shipped_name
