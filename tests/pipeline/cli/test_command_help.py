"""``sss-locus --help``: its one-line description names every command the parser accepts."""

from __future__ import annotations

import re

import pytest

from sss_locus.pipeline.cli.command import main


def test_the_help_line_names_every_command(capsys):
    with pytest.raises(SystemExit) as stop:
        main(["--help"])
    assert stop.value.code == 0
    text = capsys.readouterr().out
    commands = set(re.search(r"\{([a-z,]+)\}", text).group(1).split(","))
    description = next(line for line in text.splitlines() if line.startswith("Command line:"))
    named = set(re.findall(r"``(?:sss-locus )?([a-z]+)``", description))
    assert len(commands) >= 7 and commands == named, f"commands not named: {sorted(commands - named)}"
