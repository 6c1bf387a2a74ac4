"""The README is a user's guide that stays true: short, the two commands first, the user's own
hardware early, its layout table naming paths that exist, and its Python example running and
printing what its comment says."""

from __future__ import annotations

import re
import shutil
import subprocess
import sys

from sss_locus import paths

README = paths.REPO_ROOT / "README.md"


def _lines() -> list[str]:
    return README.read_text(encoding="utf-8").splitlines()


def test_readme_is_short_with_the_two_commands_and_own_hardware_first():
    lines = _lines()
    assert len(lines) <= 150
    first_screen = "\n".join(lines[:25])
    assert "make book" in first_screen and "make test" in first_screen
    heading = next(i for i, line in enumerate(lines) if line.startswith("## ") and "own sonar" in line)
    assert heading < 60


def test_no_issue_numbers_or_development_log_in_readme_or_book():
    pages = [README, *sorted(paths.BOOK_DIR.glob("*.md"))]
    for page in pages:
        text = page.read_text(encoding="utf-8")
        assert not re.search(r"\bissues? #?\d+|(?<![\w&])#\d+\b", text, re.I), page
        assert not re.search(r"\b(this|earlier) rounds?\b", text, re.I), page


def test_layout_table_names_existing_paths():
    rows = [line for line in _lines() if line.startswith("| `")]
    assert len(rows) >= 8
    generated = {"_build/", ".cache/", ".venv/"}
    for row in rows:
        for name in re.findall(r"`([^`]+)`", row.split("|")[1]):
            if name not in generated:
                assert (paths.REPO_ROOT / name).exists(), name


def test_python_example_runs_and_prints_the_stated_length(tmp_path):
    text = README.read_text(encoding="utf-8")
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert len(blocks) == 1
    shutil.copy(paths.DATA_DIR / "examples" / "my_auv.toml", tmp_path / "my_auv.toml")  # as the README's cp
    run = subprocess.run([sys.executable, "-c", blocks[0]], cwd=tmp_path, capture_output=True, text=True,
                         timeout=300)
    assert run.returncode == 0, run.stderr
    length = float(run.stdout.split()[-1])
    stated = re.search(r"print\(locus\.length\)\s*#\s*([0-9.]+) m", blocks[0])
    assert stated and length > 0 and f"{length:.2f}" == stated.group(1)


def test_the_chapters_user_run_commands_name_their_area():
    """A command a chapter gives for the reader's own inputs (``--data``, ``--set``, an area or an
    observations file) needs ``--name``: without it the command is refused (it would replace the
    reproduction), so a chapter must not print it that way."""
    import json

    found = []
    for path in sorted((paths.REPO_ROOT / "notebooks").glob("*.ipynb")):
        cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
        text = "\n".join("".join(c["source"]) for c in cells if c["cell_type"] == "markdown")
        blocks = [line for b in re.findall(r"```bash\n(.*?)```", text, re.S) for line in b.replace("\\\n", " ").splitlines()]
        inline = [span.replace("\n", " ") for span in re.findall(r"`(sss-locus (?:run|book)[^`]*)`", text)]
        for command in (c.strip() for c in blocks + inline if c.strip().startswith("sss-locus ")):
            if re.search(r"--data|--set|-p (area|observations)\b", command):
                found.append(command)
                assert "--name" in command, f"{path.name}: {command}"
    assert len(found) >= 2, found  # the chapters do give such commands


def test_the_own_hardware_commands_start_from_an_environment_a_make_target_builds_alone():
    """The "< 1 min" answer must not wait for the whole book: the README and the book's pages
    activate ``.venv`` after a ``make`` target that exists and builds only the environment, and
    the data file's tables are named (a platform without its noise table is refused by most
    chapters)."""
    makefile = (paths.REPO_ROOT / "Makefile").read_text(encoding="utf-8")
    lines = _lines()
    start = next(i for i, line in enumerate(lines) if line.startswith("## ") and "own sonar" in line)
    section = "\n".join(lines[start:start + 15])
    assert "noise.toml" in section and "survey.toml" in section
    pages = [section] + [(paths.BOOK_DIR / name).read_text(encoding="utf-8") for name in ("your_hardware.md", "rerun.md")]
    for text in pages:
        first = text.index("source .venv/bin/activate")
        near = text[max(0, first - 120):first + 120]
        assert "make venv" in near and "after make book or make test" not in near, near
    assert re.search(r"^venv:\s*\$\(STAMP\)\s*$", makefile, re.M)  # the target builds .venv and nothing else
    assert re.search(r"^test:.*\n\t.*pytest", makefile, re.M) and re.search(r"^book:", makefile, re.M)
