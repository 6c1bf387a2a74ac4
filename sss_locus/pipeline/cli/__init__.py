"""The ``sss-locus`` command line: ``run``, ``book``, ``answer``, ``xtf``.
"""
