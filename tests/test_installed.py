"""The package installed from its wheel works outside a source checkout (issue 41).

The wheel is built from a copy of the checkout's packaged files (``pip wheel``, offline, with this
environment's setuptools), installed into a fresh virtual environment that sees this
environment's dependencies but not the checkout, inside a git repository of the user's own, and
``sss-locus answer`` and ``sss-locus run`` run from a folder that is not the checkout: the shipped
data (``data/``), the chapters (``notebooks/``) and the book's sources come from the wheel, the
results go to the working folder, and a data directory (``--data-dir``/``SSS_LOCUS_DATA_DIR``)
layers the user's files over the shipped data.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import subprocess
import sys
import sysconfig
import tomllib
from pathlib import Path

import pytest

from sss_locus import paths
from sss_locus.pipeline.run.registry import load_registry
from sss_locus.pipeline.run.runner import resolve_parameters

#: What ``pip wheel`` reads: the metadata, setup.py and the folders that go into the wheel.
PACKAGED = ("pyproject.toml", "setup.py", "MANIFEST.in", "README.md", "LICENSE", "sss_locus", "data", "notebooks",
            "book", "_config.yml", "_toc.yml", "CITATION.cff")
#: What the wheel ships under ``sss_locus/_shipped/``, as in the checkout.
SHIPPED = ("data", "notebooks", "book", "_config.yml", "_toc.yml", "CITATION.cff")


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    """``(python, sss-locus)`` of a virtual environment with the wheel installed."""
    tmp = tmp_path_factory.mktemp("installed")
    source = tmp / "source"
    for name in PACKAGED:
        src = paths.REPO_ROOT / name
        if src.is_dir():
            shutil.copytree(src, source / name, ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
        else:
            source.mkdir(exist_ok=True)
            shutil.copy2(src, source / name)
    run = dict(capture_output=True, text=True, timeout=300)
    git = ["git", "-C", str(tmp), "-c", "user.name=u", "-c", "user.email=u@x"]  # the user's own repository
    subprocess.run([*git[:3], "init", "-q"], check=True, **run)
    subprocess.run([*git, "commit", "-q", "--allow-empty", "-m", "mine"], check=True, **run)
    built = subprocess.run([sys.executable, "-m", "pip", "wheel", str(source), "--no-deps", "--no-index",
                            "--no-build-isolation", "-w", str(tmp / "wheel"), "-q"], **run)
    assert built.returncode == 0, built.stderr[-3000:]
    venv = tmp / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True, **run)
    python = venv / "bin" / "python"
    site = subprocess.run([str(python), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                          check=True, **run).stdout.strip()
    Path(site, "deps.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")  # the dependencies only
    wheel = next((tmp / "wheel").glob("sss_locus-*.whl"))
    done = subprocess.run([sys.executable, "-m", "pip", "--python", str(python), "install", "--no-deps",
                           "--no-index", "-q", str(wheel)], **run)
    assert done.returncode == 0, done.stderr[-3000:]
    return python, venv / "bin" / "sss-locus"


def _digests(root: Path) -> dict[str, str]:
    """SHA-256 of every shipped file under ``root`` (a checkout, or the installed ``_shipped``)."""
    files = [root / name for name in SHIPPED if (root / name).is_file()]
    files += [f for name in SHIPPED if (root / name).is_dir() for f in (root / name).rglob("*") if f.is_file()]
    return {f.relative_to(root).as_posix(): hashlib.sha256(f.read_bytes()).hexdigest()
            for f in files if "__pycache__" not in f.parts}


def test_the_wheel_carries_the_shipped_files_as_in_the_checkout_and_finds_them(installed, tmp_path):
    """Data, chapters and the book's sources, byte for byte, found through importlib.resources;
    the book stages from them into the working folder."""
    python, sss_locus = installed
    code = ("import json, sss_locus, sss_locus.paths as p\n"
            "from sss_locus.pipeline.run.registry import load_registry\n"
            "from sss_locus.pipeline.book import bookbuild\n"
            "print(sss_locus.__file__); print(p.IN_CHECKOUT); print(p.REPO_ROOT)\n"
            "print(load_registry()['planning'].source_relative)\n"
            "print(bookbuild.stage())\n"
            "from sss_locus.pipeline.run.runner import resolve_parameters\n"  # the worked examples' files
            "for name in ('your_pings', 'survey_design'):\n"
            "    print(json.dumps(resolve_parameters(load_registry()[name], 'quick', {}, from_text=True)))")
    out = subprocess.run([str(python), "-c", code], cwd=tmp_path, capture_output=True, text=True, timeout=120,
                         env=_user_environment())
    assert out.returncode == 0, out.stderr[-3000:]
    where, in_checkout, root, planning, staged, pings, design = out.stdout.splitlines()
    assert not Path(where).is_relative_to(paths.REPO_ROOT) and in_checkout == "False"
    assert Path(root) == Path(where).parent / "_shipped"  # inside the installed package
    assert _digests(Path(root)) == _digests(paths.REPO_ROOT) and "book/intro.md" in _digests(Path(root))
    assert planning == "notebooks/planning.ipynb"  # as a checkout's manifests name it
    for name, installed_values in (("your_pings", pings), ("survey_design", design)):  # found, named as in a checkout
        assert json.loads(installed_values) == json.loads(json.dumps(
            resolve_parameters(load_registry()[name], "quick", {}, from_text=True)))
    assert json.loads(design)["area"] == "data/examples/survey_area.toml"
    assert json.loads(design)["area_sha256"] == _sha256(paths.DATA_DIR / "examples" / "survey_area.toml")
    assert Path(staged) == tmp_path / "_build" / "source"  # the book stages into the working folder
    assert (Path(staged) / "_toc.yml").read_bytes() == paths.TOC_FILE.read_bytes()
    assert (Path(staged) / "book" / "references.bib").read_bytes() == (paths.BOOK_DIR / "references.bib").read_bytes()
    # this environment sees Jupyter Book's package but has no jupyter-book command: one line, before any run
    refused = subprocess.run([str(sss_locus), "book"], cwd=tmp_path, capture_output=True, text=True, timeout=120,
                             env=_user_environment())
    assert refused.returncode == 2 and refused.stderr.count("\n") == 1, refused.stderr
    assert "needs jupyter-book" in refused.stderr and "sss-locus[book]" in refused.stderr


def _user_environment(**settings: str) -> dict[str, str]:
    """This process's environment without the project's settings, plus ``settings``."""
    return {**{k: v for k, v in os.environ.items() if not k.startswith("SSS_LOCUS_")}, **settings}


def test_a_chapter_runs_from_any_folder_over_a_data_directory(installed, tmp_path):
    """``sss-locus run`` from a folder of the user's: the notebook comes from the wheel, the
    results go to ``_build/`` there (nothing into the installed package), and a data directory
    changes the value a caption states; its manifest names the shipped and the user's files with
    their SHA-256, and no git commit (the environment lies in the user's own repository)."""
    python, sss_locus = installed
    package = Path(subprocess.run([str(python), "-c", "import sss_locus.paths as p; print(p.PACKAGE_DIR)"],
                                  cwd=tmp_path, capture_output=True, text=True, check=True, timeout=120).stdout.strip())
    assert package.is_relative_to(python.parent.parent)  # the installed package, not the checkout

    def package_files():
        return {f for f in package.rglob("*") if "__pycache__" not in f.parts}

    before = package_files()
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "sonar.toml").write_text('[sonars.edgetech_2205.azimuth_deg]\nvalue = 100.0\nassumption = "ours"\n')
    shipped = tomllib.loads((paths.DATA_DIR / "platforms.toml").read_text())["sonars"]["edgetech_2205"]
    assert shipped["azimuth_deg"]["value"] != 100.0
    bad = subprocess.run([str(sss_locus), "run", "concept", "--data-dir", "nowhere"], cwd=tmp_path,
                         capture_output=True, text=True, timeout=120, env=_user_environment())
    assert bad.returncode == 2 and bad.stderr == "sss-locus run: error: --data-dir nowhere does not exist\n"
    inside = subprocess.run([str(sss_locus), "run", "concept"], cwd=package, capture_output=True, text=True,
                            timeout=120, env=_user_environment())
    assert inside.returncode == 2 and "lies inside the installed package" in inside.stderr, inside.stderr
    ran = subprocess.run([str(sss_locus), "run", "concept", "--profile", "quick", "--name", "mine"], cwd=tmp_path,
                         capture_output=True, text=True, timeout=600,
                         env=_user_environment(SSS_LOCUS_DATA_DIR=str(mine)))
    assert ran.returncode == 0, ran.stderr[-3000:]
    area = tmp_path / "_build" / "mine" / "source"
    assert (area / "executed" / "concept.ipynb").is_file()
    manifest = json.loads((area / "_extra" / "figures" / "fig-locus-concept.json").read_text())
    assert "the 100° azimuth aperture of the EdgeTech 2205" in manifest["caption"]
    files = {f["path"]: (f["role"], f["sha256"]) for f in manifest["data_inputs"]["files"]}
    assert files == {"data/platforms.toml": ("shipped", _sha256(paths.DATA_DIR / "platforms.toml")),
                     "sonar.toml": ("user", _sha256(mine / "sonar.toml"))}
    assert manifest["git_commit"] == "unknown"
    assert package_files() == before  # nothing written into the installed package
    assert {p.name for p in tmp_path.iterdir()} - {".cache"} == {"_build", "mine"}  # the results are here


def _sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def test_answer_runs_from_any_folder_with_the_installed_package(installed, tmp_path):
    """README's first command, from a folder holding only the user's file, prints what the
    checkout's command prints (the same data files, entries and numbers)."""
    _, sss_locus = installed
    shutil.copy2(paths.DATA_DIR / "examples" / "my_auv.toml", tmp_path / "my_auv.toml")
    argv = ["answer", "--data", "my_auv.toml", "-p", "platform", "my_auv"]
    env = {k: v for k, v in os.environ.items() if not k.startswith("SSS_LOCUS_")}
    out = subprocess.run([str(sss_locus), *argv], cwd=tmp_path, capture_output=True, text=True, timeout=300, env=env)
    assert out.returncode == 0, out.stderr[-3000:]
    assert (tmp_path / ".cache").is_dir() and not (paths.REPO_ROOT / "my_auv.toml").exists()
    checkout = subprocess.run([sys.executable, "-m", "sss_locus.pipeline.cli.command", *argv], cwd=tmp_path,
                              capture_output=True, text=True, timeout=300,
                              env={**env, "SSS_LOCUS_CACHE_DIR": str(tmp_path / "checkout-cache")})
    assert checkout.returncode == 0, checkout.stderr[-3000:]

    def shown(text):
        return [line for line in text.splitlines() if not line.startswith("computed in")]

    assert shown(out.stdout) == shown(checkout.stdout)
    assert "data: my_auv.toml (user" in out.stdout and "Top drivers of locus length" in out.stdout
