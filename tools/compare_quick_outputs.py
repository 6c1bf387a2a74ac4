"""Check that a change preserves behaviour: quick-profile outputs, bit for bit, against a git ref.

Runs ``sss-locus book --profile quick`` twice, once on a clean worktree of ``REF`` (default
``HEAD~1``) and once on this checkout (or on a second ref with ``--against``), each with its own
build area and cache, then compares

* every figure data file (``<build>/_extra/figures/*.csv``) byte for byte, and
* every table a notebook displays (HTML of each DataFrame output, with pandas Styler's random
  table id masked) and every glued text value of the reference (``myst_nb.glue``), per
  notebook, in order. Glue keys only the new run has are listed, not counted as differences.

Glued values listed by ``--ignore`` (regular expressions; by default the run-time glue keys,
which measure the machine, not the science) are left out. Usage, from the repository root::

    .venv/bin/python tools/compare_quick_outputs.py            # this checkout vs HEAD~1
    .venv/bin/python tools/compare_quick_outputs.py main~3     # this checkout vs main~3

Exit status 0 when everything is identical, 1 when anything differs (a list of differences is
printed), 2 when a build fails. The extracted outputs of a clean ref are kept under
``_build/compare/<commit>.json`` so a second comparison against the same ref does not rebuild it.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
DEFAULT_IGNORE = (r"runtime", r"-time-s$", r"elapsed", r"cpu-s$")


def _cli_module(tree: Path) -> str:
    """The CLI module of a tree (it moved into ``sss_locus/pipeline/`` with the four layers, then
    into the pipeline's ``cli/`` room, issue 41)."""
    for module in ("sss_locus.pipeline.cli.command", "sss_locus.pipeline.cli"):
        if (tree / (module.replace(".", "/") + ".py")).exists():
            return module
    return "sss_locus.cli"


def build_quick(tree: Path, work: Path) -> Path:
    """Build the quick-profile book of ``tree`` into ``work/build``; return the build folder."""
    build, cache = work / "build", work / "cache"
    shutil.rmtree(build, ignore_errors=True)
    env = dict(os.environ, PYTHONPATH=str(tree), SSS_LOCUS_BUILD_DIR=str(build),
               SSS_LOCUS_CACHE_DIR=str(cache))
    cmd = [sys.executable, "-m", _cli_module(tree), "book", "--profile", "quick", "--force"]
    print(f"== building quick profile of {tree}", flush=True)
    result = subprocess.run(cmd, cwd=tree, env=env, capture_output=True, text=True)
    if result.returncode != 0:
        sys.stderr.write(result.stdout[-4000:] + result.stderr[-4000:])
        raise SystemExit(2)
    return build


def _glue_and_tables(notebook: Path) -> dict:
    """Glued text values and displayed tables of one executed notebook."""
    cells = json.loads(notebook.read_text(encoding="utf-8"))["cells"]
    glue, tables = {}, []
    for cell in cells:
        for out in cell.get("outputs", []):
            data = out.get("data", {})
            scrap = out.get("metadata", {}).get("scrapbook")
            if scrap is not None:  # myst_nb.glue: mime types carry a prefix when display=False
                prefix = scrap.get("mime_prefix", "")
                data = {k[len(prefix):]: v for k, v in data.items() if k.startswith(prefix)}
                text = data.get("text/markdown", data.get("text/plain"))
                if text is not None and not any(k.startswith("image/") for k in data):
                    glue[scrap["name"]] = "".join(text)
                continue
            html = "".join(data.get("text/html", ""))
            if "<table" in html:
                tables.append(html)
    return {"glue": glue, "tables": tables}


def extract(build: Path) -> dict:
    """Everything compared, from one build area (staged source in ``source/`` since the four
    layers, at the build root before)."""
    if (build / "source").is_dir():
        build = build / "source"
    figures = build / "_extra" / "figures"
    csv = {p.name: hashlib.sha256(p.read_bytes()).hexdigest() for p in sorted(figures.glob("*.csv"))}
    notebooks = {p.stem: _glue_and_tables(p) for p in sorted((build / "executed").glob("*.ipynb"))}
    return {"csv": csv, "notebooks": notebooks}


def outputs_of_ref(ref: str) -> dict:
    commit = subprocess.run(["git", "rev-parse", ref], cwd=REPO, capture_output=True, text=True,
                            check=True).stdout.strip()
    saved = REPO / "_build" / "compare" / f"{commit}.json"
    if saved.exists():
        print(f"== using saved outputs of {ref} ({commit[:12]})")
        return json.loads(saved.read_text())
    with tempfile.TemporaryDirectory(prefix="sss-compare-") as tmp:
        tree = Path(tmp) / "tree"
        subprocess.run(["git", "worktree", "add", "--detach", str(tree), commit], cwd=REPO,
                       check=True, capture_output=True)
        try:
            result = extract(build_quick(tree, Path(tmp)))
        finally:
            subprocess.run(["git", "worktree", "remove", "--force", str(tree)], cwd=REPO,
                           capture_output=True)
    saved.parent.mkdir(parents=True, exist_ok=True)
    saved.write_text(json.dumps(result, indent=1, sort_keys=True))
    return result


def compare(old: dict, new: dict, ignore: list[re.Pattern]) -> list[str]:
    problems = []
    for name in sorted(set(old["csv"]) | set(new["csv"])):
        a, b = old["csv"].get(name), new["csv"].get(name)
        if a != b:
            problems.append(f"figure data {name}: " + ("missing after" if b is None else
                                                       "new" if a is None else "bytes differ"))
    for nb in sorted(set(old["notebooks"]) | set(new["notebooks"])):
        a, b = old["notebooks"].get(nb), new["notebooks"].get(nb)
        if a is None or b is None:
            problems.append(f"notebook {nb}: {'missing after' if b is None else 'new'}")
            continue
        # every key of the reference must keep its value; keys only the new run glues (such as
        # the figure captions publish() glues) are additions, listed but not differences
        added = sorted(set(b["glue"]) - set(a["glue"]))
        if added:
            print(f"  {nb}: {len(added)} new glue key(s), e.g. {added[:3]}")
        keys = {k for k in a["glue"] if not any(p.search(k) for p in ignore)}
        for key in sorted(keys):
            if a["glue"].get(key) != b["glue"].get(key):
                problems.append(f"{nb} glue {key}: {a['glue'].get(key)!r} -> {b['glue'].get(key)!r}")
        # pandas Styler gives every rendered table a random id (T_1a2b3)
        mask = lambda tables: [re.sub(r"T_[0-9a-f]{5}", "T_id", t) for t in tables]  # noqa: E731
        if mask(a["tables"]) != mask(b["tables"]):
            problems.append(f"{nb}: displayed tables differ ({len(a['tables'])} before, "
                            f"{len(b['tables'])} after)")
    return problems


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("ref", nargs="?", default="HEAD~1", help="git ref to compare against")
    parser.add_argument("--against", help="a second ref instead of this checkout")
    parser.add_argument("--build", type=Path,
                        help="compare an existing build area (e.g. one notebook run with "
                             "SSS_LOCUS_BUILD_DIR) instead of building this checkout; only its "
                             "notebooks and figure files are compared")
    parser.add_argument("--ignore", action="append", default=list(DEFAULT_IGNORE),
                        help="regular expression of glue keys to skip (repeatable)")
    args = parser.parse_args(argv)
    old = outputs_of_ref(args.ref)
    if args.against:
        new = outputs_of_ref(args.against)
    elif args.build:
        new = extract(args.build)
        if not new["notebooks"]:  # nothing compared is no evidence of "identical"
            print(f"compare_quick_outputs: --build {args.build} holds no executed notebook "
                  "(expected <build>/source/executed/*.ipynb)", file=sys.stderr)
            return 2
        old = {"csv": {k: v for k, v in old["csv"].items() if k in new["csv"]},
               "notebooks": {k: v for k, v in old["notebooks"].items() if k in new["notebooks"]}}
    else:
        with tempfile.TemporaryDirectory(prefix="sss-compare-") as tmp:
            new = extract(build_quick(REPO, Path(tmp)))
    problems = compare(old, new, [re.compile(p) for p in args.ignore])
    n_glue = sum(len(v["glue"]) for v in new["notebooks"].values())
    n_tables = sum(len(v["tables"]) for v in new["notebooks"].values())
    print(f"compared {len(new['csv'])} figure CSVs, {n_glue} glued values, {n_tables} tables "
          f"in {len(new['notebooks'])} notebooks")
    if problems:
        print(f"{len(problems)} difference(s):")
        print("\n".join("  " + p for p in problems))
        return 1
    print("identical")
    return 0


if __name__ == "__main__":
    sys.exit(main())
