"""Package data of the wheel (the metadata is in pyproject.toml).

The project's shipped files stay where they are in the repository and are installed under
``sss_locus/_shipped/`` laid out as in a checkout, so an installed package (``pip install .``, no
checkout) finds them (:mod:`sss_locus.paths`): the inputs (``data/``), the chapters
(``notebooks/``, with ``registry.toml``) and the book's own sources (``book/``, ``_config.yml``,
``_toc.yml``, ``CITATION.cff``), so that ``sss-locus run`` and ``sss-locus book`` work from any
folder.
"""

from pathlib import Path

from setuptools import find_packages, setup
from setuptools.command.build_py import build_py

SHIPPED = {"sss_locus._shipped.data": "data", "sss_locus._shipped.notebooks": "notebooks",
           "sss_locus._shipped.book": "book"}
#: Single files of the repository's root the book build reads, copied to ``sss_locus/_shipped/``.
SHIPPED_FILES = ("_config.yml", "_toc.yml", "CITATION.cff")


class BuildPy(build_py):
    """``build_py`` that also copies :data:`SHIPPED_FILES` into the wheel's ``sss_locus/_shipped/``
    (an editable install reads them from the checkout and needs no copy)."""

    def run(self):
        super().run()
        if not getattr(self, "editable_mode", False):
            for name in SHIPPED_FILES:
                self.copy_file(name, str(Path(self.build_lib, "sss_locus", "_shipped", name)))


setup(
    packages=find_packages(include=["sss_locus", "sss_locus.*"]) + list(SHIPPED),
    package_dir=SHIPPED,
    package_data={
        "sss_locus._shipped.data": ["*.toml", "*.md", "examples/*.toml", "examples/**/*"],
        "sss_locus._shipped.notebooks": ["*.ipynb", "registry.toml"],
        "sss_locus._shipped.book": ["*.md", "*.bib"],
    },
    include_package_data=False,
    cmdclass={"build_py": BuildPy},
)
