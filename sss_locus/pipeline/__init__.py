"""Running the notebooks and building the book: registry, runner, cache, figure export and
provenance, book build and the ``sss-locus`` command line.

Rooms (grouped by job; CONTRIBUTING.md, "Architecture"):

``run/``
    Running notebooks: registry, runner, kernels, cache, atomic commits, preflight checks,
    budgets, progress, a user's files as parameters. Modules: ``atomic``, ``budgets``,
    ``cache``, ``context``, ``faults``, ``kernels``, ``orphans``, ``outputs``,
    ``paramcell``, ``params``, ``preflight``, ``progress``, ``registry``, ``runner``, ``scaleout``,
    ``transaction``, ``userfiles``.
``publish/``
    Publishing: citable figures and tables, provenance, citation metadata, readability, mission
    files. Modules: ``citation``, ``export``, ``geojson7946``, ``latex_ascii``, ``missions``,
    ``provenance``, ``publish``, ``readability``, ``table_export``.
``book/``
    Building the book: staging, indexes, the claims page, build areas, the PDF. Modules:
    ``areanotice``, ``areas``, ``bookbuild``, ``bookpdf``, ``buildlog``, ``claimsindex``,
    ``failedchapters``, ``figindex``, ``paperinputs``, ``pdfcheck``, ``pdflinks``, ``studies``.
``chapters/``
    One facade per chapter: everything its notebook calls, in one import. Modules: ``common``,
    ``concept``, ``derivation``, ``noise``, ``planning``, ``pose_space``, ``reconstruction``,
    ``rigs``, ``survey_passes``, ``three_views``, ``water``, ``your_pings``; ``params/``: every
    chapter's parameters model (``params/<notebook>.py``).
``cli/``
    The ``sss-locus`` command line: ``run``, ``book``, ``answer``, ``xtf``. Modules: ``answer``,
    ``command``, ``xtfinfo``.
"""

from sss_locus.pipeline.run import context  # noqa: F401
