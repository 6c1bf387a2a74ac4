"""Command line: ``sss-locus run``, ``book``, ``answer``, ``xtf``, ``params``, ``list`` and ``cache``.

Examples::

    sss-locus run pose_space --profile quick -p n_samples 500 -p seed 3
    sss-locus params pose_space          # the valid parameters, types and defaults
    sss-locus book                       # every notebook with its `book` profile, then the site
    sss-locus book --profile quick       # the same from the fast profile
    sss-locus book --no-run              # rebuild the site from the executed copies as they are
    sss-locus cache --prune              # cache size; delete entries no current input reaches
    sss-locus run pose_space --data my.toml -p platforms '["my_auv"]' --name my_auv  # your sonar and vehicle
    sss-locus book --data my.toml -p platforms '["my_auv"]' --name my_auv  # its book: _build/my_auv/html
    sss-locus answer --data my.toml -p platform my_auv  # bands and drivers in the terminal, no book
    sss-locus xtf survey.xtf             # channels, sample order, pings, layback of an XTF file

A run on other inputs than the paper's (--data, --set, other platforms) goes into a build area of
its own with --name; into the reproduction (_build/) it is refused unless --replace-reproduction.
A side run (--output PATH) writes only beside PATH, which must lie outside _build/ (the
reproduction and every named area, whatever --name says); --replace-reproduction is refused with it.

Every parameter value is checked (type, range, allowed values, memory) before a kernel starts.
A failing notebook is reported in one line (cell and error); add --verbose for the traceback.

Where things are: the notebooks and the shipped data come from the checkout, or from the installed
package (sss_locus/_shipped/, shown by `sss-locus list`). Results go to the build area _build/ (the
executed copies in _build/source/executed/, figures and tables in _build/source/_extra/figures/,
the site in _build/html/; _build/NAME with --name) and the result cache to .cache/: in the
checkout, else in the folder the command is started in, never into the installed package
(SSS_LOCUS_BUILD_DIR and SSS_LOCUS_CACHE_DIR move them). Your data: --data FILE, --data-dir DIR
(or SSS_LOCUS_DATA_DIR: a folder of such files) and --set, layered over the shipped data.
"""

from __future__ import annotations

import argparse
import os
import sys
import time

from sss_locus import paths
from sss_locus.pipeline.book import areas
from sss_locus.pipeline.run import scaleout
from sss_locus.pipeline.run.registry import RENAMED, ParameterError, get_entry, load_registry


def _data_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--data", action="append", default=[], metavar="FILE.toml",
                        help="your data file (schema of data/*.toml): its sonars, platforms, envelopes, "
                        "offset_models, noise, terrain and survey tables add to or override the shipped ones by key "
                        "(repeatable; validated before any notebook starts)")
    parser.add_argument("--data-dir", metavar="DIR", default=os.environ.get(paths.DATA_DIR_ENV) or None,
                        help="your data directory: every DIR/*.toml is read as if given with --data (name "
                        f"order, before the --data files; default: ${paths.DATA_DIR_ENV} when set)")
    parser.add_argument("--set", action="append", default=[], metavar="KEY.PATH=VALUE", dest="set_values",
                        help="override one data value, e.g. platforms.auv.transducers.port.tilt_deg=15 "
                        "(repeatable; recorded as a user override)")


def _data_inputs(args: argparse.Namespace):
    """Validate --data/--set before anything runs; activate them in this process (the
    parameters that are data keys (:class:`~sss_locus.pipeline.run.params.DataKeys`) then
    see the user's keys)."""
    from sss_locus.experiments.datamodel import userdata

    files = list(args.data)
    if args.data_dir is not None:
        given = args.data_dir != os.environ.get(paths.DATA_DIR_ENV)  # else read from the environment
        files[:0] = userdata.directory_files(args.data_dir, "--data-dir" if given else paths.DATA_DIR_ENV)
    inputs = userdata.use(files, args.set_values)
    for flag in userdata.hardware_flags(inputs):  # possible, but probably a mistake
        print(f"sss-locus {args.command}: warning: {flag}", file=sys.stderr)
    return inputs


def _area_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--name", metavar="NAME",
                        help="work in the build area _build/NAME (its own executed copies, figures and "
                        "site _build/NAME/html) instead of the reproduction in _build/")
    parser.add_argument("--replace-reproduction", action="store_true",
                        help="allow a run on other inputs than the paper's (--data, --set, other platforms) "
                        "to replace the reproduction's chapters, figures and claims table")


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="sss-locus", description=__doc__.split("\n")[0],
                                     epilog=__doc__.split("\n\n", 1)[1],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)

    run = sub.add_parser("run", help="execute one notebook with parameters into its executed copy")
    run.add_argument("notebook", help="registry name (e.g. pose_space) or notebooks/<name>.ipynb")
    run.add_argument("--profile", default="book", help="parameter profile from notebooks/registry.toml (default: book)")
    run.add_argument("-p", "--parameter", nargs=2, action="append", default=[], metavar=("NAME", "VALUE"),
                     help="override one parameter (repeatable); VALUE is converted to the declared type")
    run.add_argument("--output", help="side run: write the executed copy here (its figures into figures/ "
                     "beside it) instead of the build area")
    run.add_argument("--verbose", action="store_true", help="show the full traceback of a failing cell")
    _data_arguments(run)
    _area_arguments(run)
    scaleout.add_arguments(run)

    book = sub.add_parser("book", help="run every notebook, then build the book")
    book.add_argument("--profile", default="book", help="parameter profile for every notebook (default: book)")
    book.add_argument("--no-run", action="store_true", help="build from the existing executed copies")
    book.add_argument("--jobs", type=int, default=min(os.cpu_count() or 1, 4),
                      help="notebooks run at the same time (default: number of CPUs, at most 4)")
    book.add_argument("--force", action="store_true",
                      help="rerun every notebook, even those whose executed copy is up to date")
    book.add_argument("--verbose", action="store_true", help="show the full traceback of a failing cell")
    book.add_argument("-p", "--parameter", nargs=2, action="append", default=[], metavar=("NAME", "VALUE"),
                      help="override one parameter in every notebook that declares it (repeatable), "
                      "e.g. -p platforms '[\"auv\", \"my_auv\"]'")
    _data_arguments(book)
    _area_arguments(book)
    scaleout.add_arguments(book)

    cache = sub.add_parser("cache", help="show the result cache's size; --prune deletes unreachable entries")
    cache.add_argument("--prune", action="store_true",
                       help="delete entries no current input reaches (other code, data or version), "
                       "broken entries and abandoned temporary files")

    params = sub.add_parser("params", help="list a notebook's parameters and profiles")
    params.add_argument("notebook")

    ans = sub.add_parser("answer", help="print the crossing angles to prefer/avoid and the top drivers of "
                         "locus length for one platform (quick profile, no book)")
    ans.add_argument("-p", "--parameter", nargs=2, action="append", default=[], metavar=("NAME", "VALUE"),
                     help="platform KEY (required), or a parameter of the planning/pose_space notebooks")
    ans.add_argument("--profile", default="quick", help="parameter profile of those notebooks (default: quick)")
    ans.add_argument("--top", type=int, default=5, help="drivers shown (default: 5)")
    ans.add_argument("--offsets", choices=("both", "independent", "matched"), default="both",
                     help="which way you fly the two passes (default: both answers): 'independent' = survey "
                     "lines flown without steering for the feature (it falls anywhere in each swath); 'matched' = "
                     "pass 2 steered to see the feature where pass 1 saw it (same side, about the same distance "
                     "across the swath)")
    _data_arguments(ans)

    xtf = sub.add_parser("xtf", help="a one-screen summary of an XTF file (channels, sides, sample order, range, "
                         "pings, time, layback), for writing a matches file")
    xtf.add_argument("file", help="the XTF file")
    xtf.add_argument("--sample-order", default="detect", choices=("detect", "near_first", "port_far_first"),
                     help="which end of each channel is the near end (default: detect it from the data)")

    sub.add_parser("list", help="list the registered notebooks")
    return parser


def _run(args: argparse.Namespace) -> int:
    from importlib.util import find_spec

    from sss_locus.pipeline.run.runner import resolve_parameters, run_notebook

    if find_spec("papermill") is None or find_spec("ipykernel") is None:
        raise RuntimeError("running a chapter needs papermill and ipykernel (the package's book extra: "
                           "pip install 'sss-locus[book]')")
    data = _data_inputs(args)
    entry = get_entry(args.notebook)
    overrides = _overrides(args.parameter)
    if args.output is None:
        parameters = resolve_parameters(entry, args.profile, overrides, from_text=True, data=data)
        areas.check_reproduction([(entry, parameters)], replace=args.replace_reproduction)
        _say_area()
    elif args.replace_reproduction:  # one rule: a side run writes beside --output and nowhere else
        raise ValueError("--replace-reproduction and --output contradict each other: a side run writes only "
                         "beside --output (outside every build area) and never replaces the reproduction; "
                         "drop one of them")
    run_notebook(entry, args.profile, overrides, from_text=True, output=args.output, data=data)
    if args.output:  # a side run leaves the book as it was: nothing to rebuild
        return 0
    if paths.build_name():
        print(f"Rebuild the site from the executed copies with: sss-locus book --name {paths.build_name()} "
              "and this run's --data/--set/-p (chapters run already are reused, the others run first)")
    else:
        print("Rebuild the site from the executed copies with: sss-locus book --no-run")
    return 0


def _overrides(pairs: list[list[str]]) -> dict[str, str]:
    overrides: dict[str, str] = {}
    for name, value in pairs:
        if name in overrides:
            raise ParameterError(f"parameter {name!r} given twice")
        overrides[name] = value
    return overrides


def _book(args: argparse.Namespace) -> int:
    from sss_locus.pipeline.book import bookbuild
    from sss_locus.pipeline.run.runner import is_up_to_date, run_many

    start = time.perf_counter()
    bookbuild.check_sources_and_tools()
    entries = load_registry()
    failure = None
    if not args.no_run:
        from sss_locus.pipeline.run.runner import declared_overrides, resolve_parameters

        data = _data_inputs(args)
        overrides = _overrides(args.parameter)
        unknown = set(overrides) - {n for e in entries.values() for n in e.parameters()}
        renamed = {f"{old!r} is now {RENAMED[old]!r}" for old in unknown if old in RENAMED}
        if renamed:
            raise ParameterError(f"renamed parameter(s): {', '.join(sorted(renamed))}")
        if unknown:
            raise ParameterError(f"no notebook has the parameter(s) {sorted(unknown)}")
        runs = [(entry, resolve_parameters(entry, args.profile, declared_overrides(entry, overrides),
                                           from_text=True, data=data))
                for entry in entries.values()]  # every notebook's parameters, validated before anything runs
        areas.check_reproduction(runs, replace=args.replace_reproduction)
        _say_area()
        stale = []
        for entry in entries.values():
            if not args.force and is_up_to_date(entry, args.profile, declared_overrides(entry, overrides), data):
                print(f"up to date: {entry.name} [{args.profile}] (same notebook, parameters, code, "
                      f"data and environment as its executed copy; --force reruns it)")
            else:
                stale.append(entry)
        try:
            run_many(stale, args.profile, jobs=args.jobs, verbose=args.verbose, overrides=overrides, data=data)
        except RuntimeError as exc:  # a named book builds with its failed chapters marked as failed
            if not paths.build_name():
                raise
            failure = exc
            print(f"sss-locus book: error: {exc}", file=sys.stderr)
    index = bookbuild.build()
    print(f"Built in {time.perf_counter() - start:.0f} s. Open the book:")
    print(index)
    if failure is not None:
        print("sss-locus book: the book was built, but the chapter(s) above failed: their pages say so",
              file=sys.stderr)
        return 1
    return 0


def _say_area() -> None:
    if paths.build_name():
        print(f"build area: {paths.build_dir()} (named {paths.build_name()!r}; the reproduction in "
              f"{paths.build_dir().parent} is not touched)")


def _params(args: argparse.Namespace) -> int:
    entry = get_entry(args.notebook)
    print(f"{entry.name}: {entry.source_relative} -> <build>/{entry.executed}")
    print("parameters:")
    for parameter in entry.parameters().values():
        print("  " + parameter.describe())
    for profile, values in entry.profiles.items():
        shown = ", ".join(f"{k}={v!r}" for k, v in values.items()) or "(notebook defaults)"
        print(f"profile {profile}: {shown}")
    return 0


def _answer(args: argparse.Namespace) -> int:
    from sss_locus.pipeline.cli.answer import answer

    keys = [value for name, value in args.parameter if name == "platform"]
    if len(keys) != 1:
        raise ParameterError("answer needs exactly one -p platform KEY (a key of the shipped data or of --data)")
    _data_inputs(args)
    answer(keys[0], args.profile, args.parameter, top=args.top, offsets=args.offsets)
    return 0


def _xtf(args: argparse.Namespace) -> int:
    from sss_locus.pipeline.cli.xtfinfo import summary_lines

    lines = summary_lines(args.file, args.sample_order)
    print("\n".join(lines))
    for line in lines:  # a file cut short: the user sees it where errors go, too
        if line.startswith("warning: "):
            print(f"sss-locus xtf: {line}", file=sys.stderr)
    return 0


def _list(_: argparse.Namespace) -> int:
    for entry in load_registry().values():
        print(f"{entry.name:20s} {entry.source_relative:35s} profiles: {', '.join(entry.profiles)}")
    print(f"notebooks: {paths.NOTEBOOKS_DIR}")
    print(f"shipped data: {paths.DATA_DIR} (copy a file from there to start your own --data file)")
    print(f"build area: {paths.build_dir()}")
    return 0


def _cache(args: argparse.Namespace) -> int:
    from sss_locus.pipeline.run import cache

    report = cache.prune() if args.prune else cache.usage()
    print(f"cache {paths.cache_dir()}: {report['entries']} entries, {report['bytes'] / 1e6:.1f} MB "
          f"({report['reachable']} reachable by the current code and data)")
    if args.prune:
        print(f"pruned {report['removed']} entries/temporary files, {report['freed'] / 1e6:.1f} MB")
    return 0


def _check_outside_package(command: str) -> None:
    """Neither the build area (``run``, ``book``) nor the result cache may lie inside the installed
    package (they default to the working folder there), before any work."""
    folders = [(paths.build_dir(), paths.BUILD_DIR_ENV)] if command in ("run", "book") else []
    for folder, setting in [*folders, (paths.cache_dir(), paths.CACHE_DIR_ENV)]:
        if not paths.IN_CHECKOUT and folder.resolve().is_relative_to(paths.PACKAGE_DIR):
            raise ValueError(f"{folder} lies inside the installed package {paths.PACKAGE_DIR}: start sss-locus "
                             f"in a folder of your own (or set {setting})")


def _check_cache_folder() -> None:
    """The result cache must be a folder this process can write (or create), before any work."""
    from sss_locus.pipeline.run.preflight import check_writable

    given = paths.cache_dir() != paths.work_root() / ".cache"  # set by $SSS_LOCUS_CACHE_DIR
    check_writable(paths.cache_dir(), f"result cache ({paths.CACHE_DIR_ENV})" if given else "result cache")


def main(argv: list[str] | None = None) -> int:
    from sss_locus.pipeline.run.runner import NotebookFailed

    args = _parser().parse_args(argv)
    handler = {"run": _run, "book": _book, "params": _params, "list": _list, "cache": _cache,
               "answer": _answer, "xtf": _xtf}[args.command]
    try:
        if args.command in ("run", "book", "answer", "cache"):
            _check_outside_package(args.command)
        if args.command in ("run", "answer") or (args.command == "book" and not args.no_run) or \
                (args.command == "cache" and args.prune):
            _check_cache_folder()
        with areas.entered(getattr(args, "name", None)):
            if args.command in ("run", "book"):
                with scaleout.scheduler_environment(args):
                    return handler(args)
            return handler(args)
    except NotebookFailed as exc:
        print(f"sss-locus {args.command}: error: {exc}", file=sys.stderr)
        if getattr(args, "verbose", False) and exc.traceback:
            print(exc.traceback, file=sys.stderr)
        elif exc.traceback:
            print("(the full traceback: add --verbose)", file=sys.stderr)
        return 1
    except KeyboardInterrupt as exc:
        print(f"sss-locus {args.command}: interrupted ({str(exc) or 'Ctrl-C'}); the last good results are "
              "unchanged", file=sys.stderr)
        return 130
    except (ValueError, FileNotFoundError, RuntimeError) as exc:  # ParameterError is a ValueError
        print(f"sss-locus {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:  # a read-only folder, a full disk: one line, no traceback
        from sss_locus.pipeline.run.transaction import describe_os_error

        print(f"sss-locus {args.command}: error: {describe_os_error(exc)}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
