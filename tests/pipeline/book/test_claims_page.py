"""The claims page cannot put a platform's number under another platform's heading.

The page states one platform order ("Platforms are always listed **AUV / boat**") and heads its
per-platform columns with it ("Measured here (AUV / boat)"). Wherever two glued numbers of
different platforms stand side by side as ``a / b`` (nothing but a slash, units and brackets
between them), ``a`` must belong to the platform listed first. Read from the page's source, so
it runs without building the book.
"""

from __future__ import annotations

import re
import tomllib

from sss_locus.paths import REPO_ROOT

CLAIMS = REPO_ROOT / "book" / "claims.md"
GLUE = re.compile(r"\{glue:text\}`(?:/executed/(?P<nb>[\w.]+)::)?(?P<key>[^`:]+)(?::[^`]*)?`")
PAIR = re.compile(r"^[^A-Za-z]*/[^A-Za-z]*(?:\bm\b[^A-Za-z]*)?$|^[^A-Za-z]*\bm\b[^A-Za-z]*/[^A-Za-z]*$")
"""Text between two glued values that pairs them ``a / b``: a slash, units (°, %, m), brackets."""
ORDER = re.compile(r"\((?:\*\*)?([A-Za-z]+) / ([A-Za-z]+)(?:\*\*)?\)|listed \*\*([A-Za-z]+) / ([A-Za-z]+)\*\*")

with open(REPO_ROOT / "data" / "platforms.toml", "rb") as _f:
    PLATFORM_KEYS = set(tomllib.load(_f)["platforms"])


def _platform(key: str) -> str | None:
    """The platform a glue key is about: the dash-separated token that is a platform key."""
    hits = [t for t in key.split("-") if t in PLATFORM_KEYS]
    return hits[0] if len(hits) == 1 else None


def _pairs(line: str):
    """Consecutive glued values of one line that stand as ``a / b``: (key_a, key_b, between)."""
    hits = list(GLUE.finditer(line))
    for a, b in zip(hits, hits[1:]):
        between = line[a.end():b.start()]
        if PAIR.match(between):
            yield a["key"], b["key"], between


def order_errors(page: str) -> list[str]:
    """Every ``a / b`` pair of glued values on ``page`` whose platforms are in the wrong order:
    the order of the enclosing table's header if it names one, else the page's."""
    page_order = None
    errors, table_order = [], None
    for n, line in enumerate(page.splitlines(), 1):
        m = ORDER.search(line)
        if m and "listed" in m.group(0):
            page_order = [m[3].lower(), m[4].lower()]
        if not line.startswith("|"):
            table_order = None
            continue
        if table_order is None:  # the header row of a table
            table_order = [m[1].lower(), m[2].lower()] if m and "listed" not in m.group(0) else page_order
            continue
        for ka, kb, between in _pairs(line):
            pa, pb = _platform(ka), _platform(kb)
            if pa and pb and pa != pb and table_order.index(pa) > table_order.index(pb):
                errors.append(f"line {n}: {ka} / {kb} (separated by {between!r}) is {pa} / {pb}, "
                              f"the table lists {' / '.join(table_order)}")
    return errors


def test_claims_page_lists_platforms_in_its_stated_order():
    page = CLAIMS.read_text(encoding="utf-8")
    assert "Platforms are always listed **AUV / boat**" in page
    assert order_errors(page) == []


def test_order_check_finds_a_swapped_pair_and_accepts_the_right_one():
    head = "Platforms are always listed **AUV / boat**.\n\n| Claim | Measured here (AUV / boat) | V |\n|---|---|---|\n"
    good = ("| c | peak at {glue:text}`/executed/s.ipynb::sp-auv-len-peak-deg:s`° "
            "({glue:text}`/executed/s.ipynb::sp-auv-len-peak-ci:s`°) / "
            "{glue:text}`/executed/s.ipynb::sp-boat-len-peak-deg:s`° (x) | **R** |\n")
    swapped = good.replace("sp-auv-len-peak-deg", "X").replace("sp-boat-len-peak-deg", "sp-auv-len-peak-deg") \
        .replace("sp-auv-len-peak-ci", "sp-boat-len-peak-ci").replace("X", "sp-boat-len-peak-deg")
    assert order_errors(head + good) == []
    errors = order_errors(head + swapped)
    assert len(errors) == 1 and "boat / auv" in errors[0]
    # words between two values ("m (AUV), then") are not an a / b pair
    prose = ("| c | {glue:text}`/executed/n.ipynb::nz-boat-extent-0:s` m (boat); at 90°: "
             "{glue:text}`/executed/n.ipynb::nz-auv-extent-90:s` | v |\n")
    assert order_errors(head + prose) == []
    # a table headed the other way round is checked against its own header
    boat_first = head.replace("(AUV / boat)", "(boat / AUV)")
    assert order_errors(boat_first + swapped) == [] and len(order_errors(boat_first + good)) == 1


# --- verdicts generated from computed flags (sss_locus.report.survey_passes.findings) ----------------------

NOTEBOOKS = REPO_ROOT / "notebooks"
TYPED_VERDICT = re.compile(r"\*\*(?:reproduced|partly|not reproduced)\b", re.IGNORECASE)


def _markdown_keys(notebook) -> set[str]:
    import json

    cells = json.loads(notebook.read_text(encoding="utf-8"))["cells"]
    text = "\n".join("".join(c["source"]) for c in cells if c["cell_type"] == "markdown")
    return {m["key"] for m in GLUE.finditer(text)}


def test_every_generated_finding_and_its_claims_row_read_one_flag():
    """A chapter's ``X-finding`` sentence and the claims page's verdict ``X-finding-verdict`` are
    written by one call from the same flags (report.survey_passes.findings); the page must glue that verdict,
    from the same notebook, and type no verdict of its own in that row."""
    page = CLAIMS.read_text(encoding="utf-8")
    page_verdicts = {(m["nb"], m["key"]) for m in GLUE.finditer(page) if m["key"].endswith("-finding-verdict")}
    findings = {(nb.stem + ".ipynb", k) for nb in sorted(NOTEBOOKS.glob("*.ipynb"))
                for k in _markdown_keys(nb) if k.endswith("-finding")}
    assert findings, "no chapter prints a generated finding"
    assert {(nb, k + "-verdict") for nb, k in findings} == page_verdicts
    for line in page.splitlines():
        if "-finding-verdict" in line:
            assert not TYPED_VERDICT.search(line), f"typed verdict beside a generated one: {line[:120]}"


def _check(all_preferred_0: bool, all_preferred_180: bool):
    import pandas as pd

    return pd.DataFrame({"end_deg": [0.0, 180.0], "end_median": [0.5, 0.4],
                         "worst_angle_deg": [10.0, 170.0], "worst_median": [8.0, 0.45], "ratio": [16.0, 1.1],
                         "n_angles": [1, 1], "all_preferred": [all_preferred_0, all_preferred_180]})


def _bands():
    import pandas as pd

    return pd.DataFrame({"kind": ["prefer", "avoid", "prefer"], "lo_deg": [0.0, 9.0, 100.0],
                         "hi_deg": [4.0, 40.0, 180.0]})


def test_near_end_finding_and_verdict_agree_for_every_pattern_of_flags():
    from sss_locus.report.survey_passes.findings import near_end_findings

    labels = {"independent": "independent", "matched:10:same": "matched ±10 m, same side"}
    for flags, word in (((True, True, True, True), "Reproduced"), ((True, True, False, True), "Partly"),
                        ((False, True, False, False), "Not reproduced")):
        checks = {("my_auv", "independent"): _check(*flags[:2]), ("boat", "matched:10:same"): _check(*flags[2:])}
        out = near_end_findings("pl", checks, {k: _bands() for k in checks}, labels, 10.0)
        sentence = out["pl-near-ends-finding"]
        assert out["pl-near-ends-finding-verdict"] == word
        assert ("not preferred everywhere" in sentence) == (word != "Reproduced")
        assert ("Every angle near both ends is preferred for" in sentence) == (word == "Partly")
        for (key, spec), check in checks.items():
            text = out[f"pl-{key.replace('_', '-')}-{spec.replace(':', '-')}-near-ends"]
            assert ("is preferred" in text and "only" not in text) == bool(check["all_preferred"].all())
            if not check["all_preferred"].all():
                assert f"{key}, {labels[spec]}" in sentence  # the failing curve is named
        if word == "Partly":  # the numbers of the failing end: 0-4 deg preferred, 8 m at 10 deg
            assert "only 0–4° is preferred (median locus length 8.00 m at 10° against 0.500 m at 0°)" in sentence


def test_noise_advice_finding_states_its_conditions_and_agrees_with_its_flags():
    from sss_locus.report.noise.findings import NOISE_WORDS, noise_advice_findings

    labels = {"independent": "independent", "matched:10:same": "matched ±10 m, same side"}
    cases = [(k, spec, s) for k in ("auv", "boat") for spec in labels for s in (1.0, 0.1)]
    for holding, word in ((set(cases), NOISE_WORDS[0]), ({("boat", "matched:10:same", 0.1)}, NOISE_WORDS[1]),
                          (set(), NOISE_WORDS[2])):
        verdicts = {c: {"holds": c in holding} for c in cases}
        out = noise_advice_findings("nz", verdicts, labels, {"auv": 0.93, "boat": 0.5})
        sentence = out["nz-advice-finding"]
        assert out["nz-advice-finding-verdict"] == word
        assert f"holds in {len(holding)} of {len(cases)} cases" in sentence
        for needed in ("independent between the two passes", "every standard deviation",
                       "noise-free locus length", "93 % (auv) / 50 % (boat)"):
            assert needed in sentence
        if word == NOISE_WORDS[1]:  # the one holding case is named as such, the others as failing
            assert ("offsets matched ±10 m, same side, every standard deviation ×0.1: holds for boat, "
                    "fails for auv") in sentence


def test_noise_advice_texts_keep_the_headline_keys_and_name_every_level():
    from sss_locus.experiments.datamodel.noise_model import NoiseModel
    from sss_locus.report.noise.figures import advice_texts, scale_text

    v = {"holds": False, "ends": 3.0, "oblique": 2.0, "perpendicular": 1.0}
    out = advice_texts("nz", {("auv", "independent", 1.0): v, ("auv", "independent", 0.1): v,
                              ("auv", "matched:10:same", 1.0): {**v, "holds": True},
                              ("auv", "matched:10:same", 0.1): v}, 1.0)
    assert out["nz-auv-x1-verdict"] == out["nz-auv-x0p1-verdict"] == "fails"
    assert out["nz-auv-matched-10-same-verdict"] == out["nz-auv-matched-10-same-x1-verdict"] == "holds"
    assert out["nz-auv-matched-10-same-x0p1-verdict"] == "fails"
    assert out["nz-auv-matched-10-same-ends-extent"] == "3.0"
    m = NoiseModel(range_resolution_m=0.0125, sound_speed_relative_sigma=0.001, horizontal_sigma_m=2.0,
                   vertical_sigma_m=0.1, roll_sigma_deg=0.1, pitch_sigma_deg=0.1, heading_sigma_deg=1.0)
    text = scale_text({"auv": m}, 0.1)  # a tenth of every value, the range cell too
    assert text.startswith("×0.1: every standard deviation")
    for part in ("range 1.25 mm", "0.010 % of the range", "position 0.20 m", "0.010 m vertical", "heading 0.10°"):
        assert part in text


# --- the count of verdicts and the index at the top of the staged page (pipeline.book.claimsindex) --

def _fake_read(values: dict[str, str]):
    def read(notebook):
        return {"cells": [{"outputs": [{"metadata": {"scrapbook": {"name": k}},
                                        "data": {"application/papermill.record/text/plain": repr(v)}}]}
                          for k, v in values.items()]}
    return read


def test_claims_index_counts_typed_glued_mixed_and_beyond_rows():
    from sss_locus.pipeline.book.claimsindex import claims_index

    page = ("# Claims\n\n## Part A\n\n| Claim (paper) | Measured | Verdict |\n|---|---|---|\n"
            "| a | x | **Reproduced.** |\n| b | x | **Partly** (test). |\n"
            "| c | x | **Not reproduced for the AUV**; **Reproduced for the boat**. |\n"
            "| d | x | **{glue:text}`/executed/planning.ipynb::pl-near-ends-finding-verdict:s`** (test) |\n\n"
            "## Open choices\n\n| Choice | This book | Alternative | Effect |\n|---|---|---|---|\n"
            "| e | f | g | **Reproduced** |\n\n"
            "## Beyond the paper: noise\n\n| Claim (paper) | Measured | Verdict |\n|---|---|---|\n"
            "| h | x | **Only without noise.** |\n")
    text, block = claims_index(page, _fake_read({"pl-near-ends-finding-verdict": "Not reproduced"}))
    assert ("1 reproduced, 2 partly, 1 not reproduced, 1 beyond the paper (5 claims" in block)
    assert text.count('<span id="claim-') == 5 and '| <span id="claim-5"></span>h |' in text
    assert "| e | f | g |" in text  # the open-choices table is not a claim
    for i, mark in ((1, "✓"), (2, "◐"), (3, "◐"), (4, "✗"), (5, "+")):
        assert f'href="#claim-{i}"' in block and f"{i}&nbsp;{mark}" in block


def test_every_claim_row_of_the_page_has_a_verdict_the_index_can_read():
    """The page's own rows all classify once their glued verdicts have values."""
    from sss_locus.pipeline.book.claimsindex import claims_index

    page = CLAIMS.read_text(encoding="utf-8")
    glued = {m["key"]: "Partly" for m in GLUE.finditer(page) if m["key"].endswith("-finding-verdict")}
    tables = [t.strip().splitlines() for t in page.split("\n\n") if t.strip().startswith("| Claim (paper)")]
    n_rows = sum(len(t) - 2 for t in tables)  # minus the header and the separator
    assert n_rows > 20
    _, block = claims_index(page, _fake_read(glued))
    assert f"({n_rows} claims" in block
