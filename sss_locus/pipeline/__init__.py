"""Running the notebooks and building the book: registry, runner, cache, figure export and
provenance, book build and the ``sss-locus`` command line.

``registry``
    ``notebooks/registry.toml``: notebooks, executed copies, parameter profiles.
``runner``
    Hermetic papermill runs, up-to-date checks.
``cache``
    ``cached(fn)``: Parquet results keyed on the function, its arguments and a fingerprint of
    ``geometry/``, ``experiments/`` and ``data/``.
``export``, ``publish``, ``provenance``
    Citable figure files with manifests and BibTeX; ``publish`` (export, glue, close) for
    notebooks; commit, environment and code fingerprints.
``bookbuild``, ``cli``
    Staging and building the Jupyter Book; the ``sss-locus`` command.
"""
