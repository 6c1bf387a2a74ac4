"""The findings generated for every platform agree, in the quick book, with the numbers the same
notebooks compute and glue by other code: the noise verdict and its smallest-extent angle (the
verdict cell's own test), the reconstruction chapter's comparison words (from the paired
intervals) and the level boat's measured crop. One source per sentence, checked on a real run."""

from __future__ import annotations

import ast
import json
from pathlib import Path

import pytest

PLATFORMS = ("auv", "boat")
NAMES = {"auv": "(`auv`)", "boat": "(`boat`)"}


def glued(executed: Path) -> dict[str, str]:
    """Every glued text of an executed notebook, by key (quotes of a plain string removed)."""
    out = {}
    for cell in json.loads(executed.read_text(encoding="utf-8"))["cells"]:
        for o in cell.get("outputs", []):
            scrap = o.get("metadata", {}).get("scrapbook")
            if scrap:
                pre, data = scrap.get("mime_prefix", ""), o["data"]
                if pre + "text/markdown" in data:
                    out[scrap["name"]] = "".join(data[pre + "text/markdown"])
                elif pre + "text/plain" in data:  # a plain string is glued as its repr
                    text = "".join(data[pre + "text/plain"])
                    try:
                        out[scrap["name"]] = ast.literal_eval(text)
                    except (ValueError, SyntaxError):
                        out[scrap["name"]] = text
    return out


def item(markdown: str, key: str) -> str:
    """The list item of platform ``key`` in a findings list."""
    return next(line for line in markdown.splitlines() if NAMES[key] in line)


def check_noise(g: dict[str, str]) -> None:
    for k in PLATFORMS:
        verdict, angle = g[f"nz-{k}-verdict"], g[f"nz-{k}-extent-min-angle"]
        for finding in ("nz-answer-generated", "nz-summary-generated"):
            text = item(g[finding], k)
            assert (f"advice {verdict}" in text) and f"smallest at {angle}°" in text, (finding, k)
        assert g[f"nz-{k}-attitude-empty"] in item(g["nz-crop-generated"], k)
        assert f"{g[f'nz-{k}-three-lost']} of the draws" in g["nz-check-generated"]


def check_reconstruction(g: dict[str, str]) -> None:
    names = {"all": "N views (ranges)", "beam": "N views + beam plane", "joint": "joint adjustment"}
    words = {"horizontal": "horizontal", "vertical": "|vertical|", "shape": "map-shape"}
    for k in PLATFORMS:
        text = item(g["rc-comparisons-generated"], k)
        for est, name in names.items():
            part = text.split(f"{name} against the mosaic: ")[1].split(". ")[0]
            for metric, word in words.items():
                said = part.split(f"{word} error ")[1].split(";")[0]
                for w in g[f"rc-{k}-{est}-{metric}-word"].split(" / "):
                    assert w in said, (k, est, metric, said)
        assert g[f"rc-{k}-flat-shape"] in item(g["rc-errors-generated"], k)


def check_water(g: dict[str, str]) -> None:
    boat = item(g["wa-surface-generated"], "boat")
    assert "cannot remove anything, exactly" in boat and g["wa-boat-pose-all-shortened_share-pct"] == "0.0 %"
    assert g["wa-boat-pose-tilt15-all-length_ratio"] in boat
    assert g["wa-auv-survey-depth2m-pass2-above"] in item(g["wa-surface-generated"], "auv")


@pytest.mark.book
@pytest.mark.parametrize("name, check", [("noise", check_noise), ("reconstruction", check_reconstruction),
                                         ("water", check_water)])
def test_generated_findings_agree_with_the_numbers_of_the_quick_book(quick_book, name, check):
    check(glued(quick_book["area"] / "source" / "executed" / f"{name}.ipynb"))
