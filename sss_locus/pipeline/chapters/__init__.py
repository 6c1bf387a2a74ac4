"""One facade per chapter: the names its notebook calls, so the import cell is one line.

``from sss_locus.pipeline.chapters import water as ch`` and then ``ch.crop_effects(...)``,
``ch.show_table(...)``, ``ch.glue(ch.key(ch.KEYS.deepest, platform=k), ...)``. A facade holds
no logic of its own: it re-exports the chapter's numbers (``experiments``), figures and prose
(``report``) and publishing (``pipeline``), plus the helpers of :mod:`.common` every chapter
shares (:func:`~.common.use_data`, :func:`~.common.show_table`, :func:`~.common.key`). It lives
in the pipeline layer because it combines all three. This package's ``__init__`` imports
nothing, so importing one chapter loads only that chapter's modules.
"""
