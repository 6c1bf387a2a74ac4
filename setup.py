"""Package data of the wheel (the metadata is in pyproject.toml).

The shipped inputs (``data/``) and the chapters (``notebooks/``, with ``registry.toml``) stay where
they are in the repository and are installed as ``sss_locus/_shipped/data`` and
``sss_locus/_shipped/notebooks``, so an installed package (``pip install .``, no checkout) finds
them (:mod:`sss_locus.paths`).
"""

from setuptools import find_packages, setup

SHIPPED = {"sss_locus._shipped.data": "data", "sss_locus._shipped.notebooks": "notebooks"}

setup(
    packages=find_packages(include=["sss_locus", "sss_locus.*"]) + list(SHIPPED),
    package_dir=SHIPPED,
    package_data={
        "sss_locus._shipped.data": ["*.toml", "*.md", "examples/*.toml", "examples/**/*"],
        "sss_locus._shipped.notebooks": ["*.ipynb", "registry.toml"],
    },
    include_package_data=False,
)
