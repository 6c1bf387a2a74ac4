"""Every file-system location the project uses, in one place.

Nothing else in the package builds a path from ``__file__`` or hard-codes a folder name: import
the constants (or call :func:`build_dir`) from here.

Layout
------
``REPO_ROOT``
    The repository checkout (the folder holding ``pyproject.toml``). An installed package (no
    checkout, :data:`IN_CHECKOUT` false) has the project's shipped files as package data laid out
    the same way, ``sss_locus/_shipped/`` (``data/``, ``notebooks/``, ``book/``, ``_config.yml``,
    ``_toc.yml``, ``CITATION.cff``; see ``setup.py``), found with :mod:`importlib.resources`,
    and that folder is ``REPO_ROOT``: every path below, and a shipped file's public name
    (``data/platforms.toml``), is the same in both. Only ``environment.lock`` is not shipped (it
    pins the checkout's environment, not an installed one's).
``DATA_DIR``
    Committed inputs with their sources (``data/``).
``NOTEBOOKS_DIR`` / ``REGISTRY_FILE``
    Notebook sources, committed without outputs, and ``notebooks/registry.toml`` listing them.
``BOOK_DIR``
    The book's own pages and ``references.bib`` (``book/``).
``build_dir()``
    The build area (git-ignored), ``_build/`` by default: the run context's
    (:mod:`sss_locus.pipeline.run.context`). Set the environment variable
    ``SSS_LOCUS_BUILD_DIR`` to put it elsewhere; the tests do this so that a test build never
    overwrites the ``book``-profile outputs. ``--name NAME`` (``sss-locus run``/``book``) makes
    ``<build>/NAME`` the build area of that command, a book of its own beside the reproduction
    (:mod:`sss_locus.pipeline.book.areas`). Inside it:

    - ``html/index.html``: the built book (where Jupyter Book users look for it),
    - ``source/``: the *staged* book source. ``sss-locus book`` copies ``_config.yml``,
      ``_toc.yml`` and ``book/`` into it next to

      - ``source/executed/<name>.ipynb``: executed notebook copies (what the book renders),
      - ``source/_extra/``: copied verbatim to the site root by Sphinx (``html_extra_path``);
        holds ``_extra/figures/<label>.{png,svg,pdf,csv,json,bib}`` (exported, citable figures,
        served by the site at ``figures/<label>.png`` etc.) and ``_extra/mathjax/`` (MathJax 3,
        served locally so math renders without internet),

    - ``jupyter-book/``: Jupyter Book's own output folder (doctrees and the site being built;
      the finished site is moved to ``html/`` only when the build succeeds),
    - ``jupyter/``: IPython, Jupyter and Matplotlib state of the kernels (hermetic runs).
    - ``tmp/``: private staging folders of runs in progress (deleted when a run ends),
    - ``failed/<name>.ipynb``: the notebook of the last failed run, for reading (never rendered),
    - ``.lock``: the build area's lock (run commits and book builds, one at a time).
``cache_dir()``
    On-disk cache of expensive results (``.cache/`` by default, git-ignored; an installed package
    without a checkout puts ``_build/`` and ``.cache/`` in the working directory; override with
    ``SSS_LOCUS_CACHE_DIR``). Entries are keyed on notebook, parameters, seed and package version,
    so a test build and the book build can share it safely.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path
from typing import Any

PACKAGE_DIR: Path = Path(__file__).resolve().parent
#: Whether the package runs from a source checkout (``pyproject.toml`` and ``data/`` beside it),
#: not from an installed wheel.
IN_CHECKOUT: bool = (PACKAGE_DIR.parent / "pyproject.toml").is_file() and (PACKAGE_DIR.parent / "data").is_dir()


def _shipped_root() -> Path:
    """The installed copy of the checkout's shipped files (package data, see ``setup.py``)."""
    from importlib.resources import files

    return Path(str(files("sss_locus") / "_shipped"))


REPO_ROOT: Path = PACKAGE_DIR.parent if IN_CHECKOUT else _shipped_root()
DATA_DIR: Path = REPO_ROOT / "data"
NOTEBOOKS_DIR: Path = REPO_ROOT / "notebooks"
REGISTRY_FILE: Path = NOTEBOOKS_DIR / "registry.toml"
BOOK_DIR: Path = REPO_ROOT / "book"
CONFIG_FILE: Path = REPO_ROOT / "_config.yml"
TOC_FILE: Path = REPO_ROOT / "_toc.yml"
LOCK_FILE: Path = REPO_ROOT / "environment.lock"
CITATION_FILE: Path = REPO_ROOT / "CITATION.cff"

#: The user's settings of the build area and the cache (read by :mod:`sss_locus.pipeline.run.context`).
BUILD_DIR_ENV = "SSS_LOCUS_BUILD_DIR"
CACHE_DIR_ENV = "SSS_LOCUS_CACHE_DIR"
#: The user's data directory of the ``sss-locus`` commands (``--data-dir``'s default): a folder of
#: TOML files in the schema of ``data/*.toml``, layered over the shipped data.
DATA_DIR_ENV = "SSS_LOCUS_DATA_DIR"

#: Folder names inside the build area (also used in ``_toc.yml`` and ``_config.yml``).
SOURCE_SUBDIR = "source"
EXECUTED_SUBDIR = "executed"
FIGURES_SUBDIR = "figures"
#: Folder whose contents Sphinx copies verbatim to the site root (``html_extra_path``).
EXTRA_SUBDIR = "_extra"
MATHJAX_SUBDIR = "mathjax"


def work_root() -> Path:
    """Where the build area and the cache go by default: the checkout, else (an installed
    package) the working directory.

    Returns
    -------
    pathlib.Path
        Absolute: the repository root in a checkout, else ``Path.cwd()``.
    """
    return REPO_ROOT if IN_CHECKOUT else Path.cwd()


def _default_areas() -> tuple[Path, str | None, Path]:
    """The areas of a process outside any run context.

    Returns
    -------
    build : pathlib.Path
        ``<work root>/_build``.
    name : None
        No named build area.
    cache : pathlib.Path
        ``<work root>/.cache``.
    """
    return work_root() / "_build", None, work_root() / ".cache"


#: ``() -> (build area, build-area name, cache folder)`` of this process: the run context's
#: (:func:`sss_locus.pipeline.run.context.current`, which installs itself here when imported; it reads
#: ``SSS_LOCUS_BUILD_DIR`` and ``SSS_LOCUS_CACHE_DIR``), else ``<repo>/_build`` and ``<repo>/.cache``.
areas_setting: Callable[[], tuple[Path, str | None, Path]] = _default_areas


def build_dir() -> Path:
    """Root of the build area: the run context's (``$SSS_LOCUS_BUILD_DIR`` or ``<repo>/_build``).

    Returns
    -------
    pathlib.Path
        The build area (not created here).
    """
    return areas_setting()[0]


def build_name() -> str | None:
    """Name of the named build area in use (``--name``), ``None`` in the reproduction's area.

    Returns
    -------
    str or None
        The ``--name`` of the build area, or None for the reproduction's own.
    """
    return areas_setting()[1]


def source_dir() -> Path:
    """Staged book source (``<build>/source``): configuration, pages, executed notebooks.

    Returns
    -------
    pathlib.Path
        ``<build>/source`` (not created here).
    """
    return build_dir() / SOURCE_SUBDIR


def executed_dir() -> Path:
    """Folder of executed notebook copies (``<build>/source/executed``).

    Returns
    -------
    pathlib.Path
        ``<build>/source/executed`` (not created here).
    """
    return source_dir() / EXECUTED_SUBDIR


def extra_dir() -> Path:
    """Staged ``html_extra_path`` folder (``<build>/source/_extra``): copied to the site root.

    Returns
    -------
    pathlib.Path
        ``<build>/source/_extra`` (not created here).
    """
    return source_dir() / EXTRA_SUBDIR


def figures_dir() -> Path:
    """Exported figures (``<build>/source/_extra/figures``), served at ``<site>/figures/``.

    Returns
    -------
    pathlib.Path
        ``<build>/source/_extra/figures`` (not created here).
    """
    return extra_dir() / FIGURES_SUBDIR


def mathjax_dir() -> Path:
    """Local MathJax 3 copy (``<build>/source/_extra/mathjax``), served at ``<site>/mathjax/``.

    Returns
    -------
    pathlib.Path
        ``<build>/source/_extra/mathjax`` (not created here).
    """
    return extra_dir() / MATHJAX_SUBDIR


def jupyter_dir() -> Path:
    """Kernel state (IPython, Jupyter data/runtime, Matplotlib config) for hermetic runs.

    Returns
    -------
    pathlib.Path
        ``<build>/jupyter`` (not created here).
    """
    return build_dir() / "jupyter"


def jupyter_book_dir() -> Path:
    """Jupyter Book's output folder (``<build>/jupyter-book``; it writes ``_build/html`` there).

    Returns
    -------
    pathlib.Path
        ``<build>/jupyter-book`` (not created here).
    """
    return build_dir() / "jupyter-book"


def html_dir() -> Path:
    """Built site (``<build>/html``).

    Returns
    -------
    pathlib.Path
        ``<build>/html`` (not created here).
    """
    return build_dir() / "html"


def index_html() -> Path:
    """The built book's front page.

    Returns
    -------
    pathlib.Path
        ``<build>/html/index.html`` (it may not exist yet).
    """
    return html_dir() / "index.html"


def cache_dir() -> Path:
    """Root of the result cache: the run context's (``$SSS_LOCUS_CACHE_DIR`` or ``<repo>/.cache``).

    Returns
    -------
    pathlib.Path
        The cache folder (not created here).
    """
    return areas_setting()[2]


def site_url(path: Path) -> str:
    """URL, relative to the site root, of a file under :func:`extra_dir` (``figures/x.png``).

    Parameters
    ----------
    path : pathlib.Path
        A file inside :func:`extra_dir` (symbolic links are resolved on both sides).

    Returns
    -------
    str
        The relative URL with ``/`` separators.

    Raises
    ------
    ValueError
        ``path`` is not inside :func:`extra_dir`.
    """
    return path.resolve().relative_to(extra_dir().resolve()).as_posix()


def public_path(path: str | os.PathLike) -> str:
    """A file as a published manifest or page names it: relative to the repository when it is
    inside it (``data/examples/my_auv.toml``), else its file name only (``myboat.toml``) — never a
    local absolute path. The file's SHA-256 beside the name identifies it. A relative path (the
    shipped ``data/platforms.toml``) is already public and is returned as it is.

    Parameters
    ----------
    path : str or os.PathLike
        A file's path, absolute or relative.

    Returns
    -------
    str
        POSIX-style path relative to the repository, the bare file name (outside it), or the
        relative path unchanged.
    """
    p = Path(path)
    if not p.is_absolute():
        return p.as_posix()
    try:
        p = p.resolve()
    except OSError:
        pass
    return p.relative_to(REPO_ROOT).as_posix() if p.is_relative_to(REPO_ROOT) else p.name


def public_values(value: Any) -> Any:
    """``value`` (a parameter value: a string, list or mapping of them) with every absolute path
    replaced by :func:`public_path`, for what is published (manifests, pages).

    Parameters
    ----------
    value : Any
        A string, list, tuple or dict of them, nested to any depth; other values (numbers,
        None) pass unchanged.

    Returns
    -------
    Any
        The same structure (tuples become lists) with absolute paths made public.
    """
    if isinstance(value, str):
        return public_path(value) if os.path.isabs(value) else value
    if isinstance(value, (list, tuple)):
        return [public_values(v) for v in value]
    if isinstance(value, dict):
        return {k: public_values(v) for k, v in value.items()}
    return value
