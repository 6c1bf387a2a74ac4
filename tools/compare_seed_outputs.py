"""Check that the book's printed numbers are stable across seeds: two builds, every glued text the
pages quote, compared at what is printed.

Builds the book twice from this checkout, with ``-p seed 1`` and ``-p seed 2`` (and the
pose-space chapter's ``check_seed`` the other one), each with its own build area and cache under
``--work`` (or compares two existing build areas given with ``--builds A B``), then takes every
glued text that a chapter's Markdown or a page of ``book/`` quotes and compares the two seeds'
texts:

* equal texts: stable;
* both with a 95 % interval (``x (95 % CI a–b)``, ``[a, b]``) or both a span (``a° to b°``):
  stable when the two intervals overlap;
* both rounding-level numbers (written ``1.2e-13``, both below 1e-6): stable (they bound a
  floating-point error, and any such value supports what is said of it);
* both one number in the same words: stable when they differ by at most one unit of the last
  printed digit. From the printed texts alone a value that straddles a rounding boundary (0.5449
  and 0.5451 print 0.54 and 0.55) cannot be told from one that moved by a whole unit, so this is a
  screen, weaker than the chapters' own checks on the values (the pose-space chapter's seed
  table); a number printed to significant figures with trailing zeros (``120``) counts its last
  digit as the units, which is stricter than the print;
* a peak angle quoted beside its interval (key ``...-peak-deg`` with a ``...-peak-ci``): stable
  when the two seeds' intervals overlap;
* peak regions in words (``θ₁ -28° to -20°, θ₂ -28°``; ``6 cells with h₂ 45° to 75° and h₃ ...``;
  cells listed as ``(0°, 0°), (180°, 180°)``): stable when each span overlaps its counterpart,
  or the two lists of cells share one;
* anything else that differs (words, lists of bands, several numbers): listed.

Sample counts (keys ending in ``-count``, ``-n``, ``-n-ends``) describe a run, not an estimate,
and are left out like the run-time keys.

Usage, from the repository root::

    .venv/bin/python tools/compare_seed_outputs.py --profile quick      # two quick books
    .venv/bin/python tools/compare_seed_outputs.py --builds _build /tmp/seed2/build

Exit status 0 when every quoted text is stable, 1 when any is not (listed, per notebook), 2 when
a build fails. Run-time keys (``runtime``, ``cpu-s``) are left out.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from compare_quick_outputs import DEFAULT_IGNORE, _glue_and_tables  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
GLUE = re.compile(r"\{glue(?::text|:md)?\}`([^`]+)`|```\{glue:md\}\s+(\S+)")
NUMBER = r"[-+−]?\d[\d,]*(?:\.\d+)?"
INTERVAL = re.compile(rf"\(95 % CI ({NUMBER})\s*[%°m]?\s*(?:–|to)\s*({NUMBER})|^\[({NUMBER}), ({NUMBER})\]$"
                      rf"|^({NUMBER})–({NUMBER})°?$")
COUNTS = r"-count$|-n$|-n-ends$"
ROUNDING = re.compile(r"^\d\.\de-\d+$")
SPAN = re.compile(rf"^({NUMBER})° to ({NUMBER})°$|^({NUMBER})°$")  # a peak region, or one bin


def quoted_keys() -> set[tuple[str, str]]:
    """(notebook, glue key) of every glued value a chapter's Markdown or a book page quotes."""
    out = set()
    pages = [(p.stem, "".join("".join(c["source"]) for c in json.loads(p.read_text())["cells"]
                              if c["cell_type"] == "markdown"))
             for p in (REPO / "notebooks").glob("*.ipynb")]
    pages += [(None, p.read_text()) for p in (REPO / "book").glob("*.md")]
    for nb, text in pages:
        for m in GLUE.finditer(text):
            ref = m.group(1) or m.group(2)
            if "::" in ref:
                path, ref = ref.split("::", 1)
                nb = Path(path).stem
                ref = ref.rsplit(":", 1)[0]
            if nb is not None and not ref.startswith("fig-"):
                out.add((nb, ref))
    return out


def _num(text: str) -> float:
    return float(text.replace(",", "").replace("−", "-").replace("+", ""))


def _unit(text: str) -> float:
    digits = text.replace(",", "").split(".")
    return 10.0 ** -len(digits[1]) if len(digits) == 2 else 1.0


def agree(a: str, b: str) -> tuple[bool, str]:
    """Whether two seeds' printed texts agree at what is printed, and the rule that decided
    (texts as glued: a plain string's ``repr``, quotes stripped here)."""
    a, b = (t[1:-1] if len(t) > 1 and t[0] == t[-1] and t[0] in "'\"" else t for t in (a, b))
    if a == b:
        return True, "equal"
    if ROUNDING.match(a) and ROUNDING.match(b):
        return max(float(a), float(b)) < 1e-6, "rounding level"
    ia, ib = INTERVAL.search(a) or SPAN.match(a.strip()), INTERVAL.search(b) or SPAN.match(b.strip())
    if ia and ib:
        ends = [sorted(_num(g) for g in m.groups() if g is not None) for m in (ia, ib)]
        return max(ends[0][0], ends[1][0]) <= min(ends[0][-1], ends[1][-1]), "intervals overlap"
    region = _regions_overlap(a, b)
    if region is not None:
        return region, "regions overlap"
    na, nb = re.findall(NUMBER, a), re.findall(NUMBER, b)
    if len(na) == len(nb) == 1 and re.sub(NUMBER, "#", a) == re.sub(NUMBER, "#", b):
        unit = max(_unit(na[0]), _unit(nb[0]))
        return abs(_num(na[0]) - _num(nb[0])) <= unit * (1 + 1e-9), "last printed digit"
    return False, "texts differ"


def _regions_overlap(a: str, b: str) -> bool | None:
    """Whether two region texts overlap (module docstring); None if they are not region texts."""
    cells = re.compile(rf"\(({NUMBER})°, ({NUMBER})°\)")
    ca, cb = cells.findall(a), cells.findall(b)
    if ca and cb and cells.sub("#", a).replace("#, ", "") == cells.sub("#", b).replace("#, ", ""):
        return bool(set(ca) & set(cb))
    span = re.compile(rf"({NUMBER})°(?: to ({NUMBER})°)?")
    sa, sb = span.findall(a), span.findall(b)
    if len(sa) != len(sb) or not sa or " to " not in a + b or span.sub("#", a).split("#")[1:] != span.sub("#", b).split("#")[1:]:
        return None
    ends = [[sorted((_num(x), _num(y or x))) for x, y in spans] for spans in (sa, sb)]
    return all(max(p[0], q[0]) <= min(p[1], q[1]) for p, q in zip(*ends))


def build(work: Path, seed: int, profile: str) -> Path:
    out = work / f"seed{seed}"
    env = dict(os.environ, SSS_LOCUS_BUILD_DIR=str(out / "build"), SSS_LOCUS_CACHE_DIR=str(out / "cache"))
    cmd = [sys.executable, "-m", "sss_locus.pipeline.cli.command", "book", "--profile", profile,
           "-p", "seed", str(seed), "-p", "check_seed", str(3 - seed)]
    print(f"== building the {profile} book with seed {seed}", flush=True)
    if subprocess.run(cmd, cwd=REPO, env=env, capture_output=True, text=True).returncode != 0:
        raise SystemExit(2)
    return out / "build"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--profile", default="book")
    parser.add_argument("--work", type=Path, default=REPO / "_build" / "seeds")
    parser.add_argument("--builds", nargs=2, type=Path, metavar=("SEED1", "SEED2"),
                        help="compare these two build areas instead of building")
    args = parser.parse_args(argv)
    builds = args.builds or [build(args.work, s, args.profile) for s in (1, 2)]
    glue = [{p.stem: _glue_and_tables(p)["glue"] for p in (b / "source" / "executed").glob("*.ipynb")}
            for b in builds]
    ignore = re.compile("|".join((*DEFAULT_IGNORE, COUNTS)))
    rows, n = [], 0
    for nb, key in sorted(quoted_keys()):
        a, b = glue[0].get(nb, {}).get(key), glue[1].get(nb, {}).get(key)
        if a is None or b is None or ignore.search(key):
            continue
        n += 1
        ok, rule = agree(a, b)
        ci = key[:-len("-deg")] + "-ci"
        if not ok and key.endswith("-peak-deg") and ci in glue[0].get(nb, {}) and ci in glue[1].get(nb, {}):
            ok, rule = agree(glue[0][nb][ci], glue[1][nb][ci])
            rule = f"its interval {rule}" if ok else rule
        if not ok:
            rows.append(f"{nb}::{key} ({rule}): {a!r} | {b!r}")
    print(f"{n - len(rows)} of {n} quoted texts agree between the two seeds at what is printed")
    print("\n".join(rows))
    return 1 if rows else 0


if __name__ == "__main__":
    raise SystemExit(main())
