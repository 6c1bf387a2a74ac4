"""Running the notebooks and building the book: registry, runner, cache, figure export and
provenance, book build and the ``sss-locus`` command line.

``registry``
    ``notebooks/registry.toml``: notebooks, executed copies, parameter profiles.
``runner``, ``outputs``, ``atomic``
    Hermetic, atomic papermill runs (staging folder, commit under the build area's lock, signals
    as exceptions), up-to-date checks and the consistency check of executed copies and figures.
``constraints``
    Ranges, allowed values and memory bounds declared in notebook parameter comments.
``cache``
    ``cached(fn)``: Parquet results keyed on the function, its arguments and a fingerprint of
    ``geometry/``, ``experiments/`` and ``data/``.
``export``, ``publish``, ``provenance``
    Citable figure files with manifests and BibTeX; ``publish`` (export, glue, close) for
    notebooks; commit, environment and code fingerprints.
``bookbuild``, ``cli``
    Staging and building the Jupyter Book; the ``sss-locus`` command.
``context``
    The run context: what every process of a run knows of it (imported here, so that whichever
    pipeline module a process loads, :mod:`sss_locus.paths` and the budgets answer from it).
"""

from sss_locus.pipeline import context  # noqa: F401
