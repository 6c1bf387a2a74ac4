"""The package installed from its wheel works outside a source checkout (issue 41).

The wheel is built from a copy of the checkout's packaged files (``pip wheel``, offline, with this
environment's setuptools), installed into a fresh virtual environment that sees this
environment's dependencies but not the checkout, and ``sss-locus answer`` runs from a folder
that is not the checkout: the shipped data (``data/``) and the chapters (``notebooks/``) come
from the wheel.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest

from sss_locus import paths

#: What ``pip wheel`` reads: the metadata, setup.py and the folders that go into the wheel.
PACKAGED = ("pyproject.toml", "setup.py", "README.md", "LICENSE", "sss_locus", "data", "notebooks")


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


def test_the_wheel_carries_the_shipped_data_and_chapters_and_finds_them(installed, tmp_path):
    python, _ = installed
    code = ("import sss_locus, sss_locus.paths as p, sys\n"
            "from sss_locus.pipeline.run.registry import load_registry\n"
            "print(sss_locus.__file__); print(p.IN_CHECKOUT); print(p.DATA_DIR)\n"
            "print(sorted(f.name for f in p.DATA_DIR.glob('*.toml')))\n"
            "print(load_registry()['planning'].source_relative)")
    out = subprocess.run([str(python), "-c", code], cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr[-3000:]
    where, in_checkout, data, tomls, planning = out.stdout.splitlines()
    assert not Path(where).is_relative_to(paths.REPO_ROOT) and in_checkout == "False"
    assert Path(data).is_relative_to(Path(where).parent)  # inside the installed package
    assert tomls == str(sorted(f.name for f in paths.DATA_DIR.glob("*.toml")))
    assert planning == "notebooks/planning.ipynb"  # as a checkout's manifests name it


def test_answer_runs_from_any_folder_with_the_installed_package(installed, tmp_path):
    """README's first command, from a folder holding only the user's file, prints what the
    checkout's command prints (the same data files, entries and numbers)."""
    import os

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
