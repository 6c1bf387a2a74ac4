"""Everything a reader sees: figures and prose, one room per chapter.

The only layer that draws (matplotlib, seaborn). Plot helpers take data and ``ax=None`` and
return the axes or the figure; :mod:`~sss_locus.report.common.style` gives platforms their names
and colours from the data, :mod:`~sss_locus.report.common.text` formats numbers for glued prose.

Rooms (shared rooms, then one per chapter of the book in ``_toc.yml`` order; CONTRIBUTING.md,
"Architecture"):

``common/``
    Shared look and words of every chapter: the seaborn theme and platform names and colours,
    numbers in prose, readable tables. Modules: ``style``, ``tables``, ``text``.
``concept/``
    The concept chapter's figures. Modules: ``figures``.
``derivation/``
    The derivation chapter's display of the algebra. Modules: ``figures``.
``rigs/``
    The rigs chapter's figures. Modules: ``figures``.
``pose_space/``
    The pose-space chapter's figures and findings. Modules: ``figures``, ``findings``.
``survey_passes/``
    The survey-pass and planning chapters' figures, findings and verdict words. Modules:
    ``figures``, ``findings``, ``planning``.
``three_views/``
    The three-view chapter's figures and findings (with the survey-pass findings: follow-up).
    Modules: ``figures``, ``findings``.
``noise/``
    The noise chapter's figures. Modules: ``figures``.
``water/``
    The water chapter's figures. Modules: ``figures``.
``reconstruction/``
    The reconstruction chapter's figures. Modules: ``figures``.
``your_pings/``
    The your-pings chapter's figures: maps, feature panels, waterfalls, the joint adjustment.
    Modules: ``figures``, ``joint``, ``real``, ``waterfall``.
``survey_design/``
    The survey-design chapter's figures and plan maps. Modules: ``figures``, ``map``.
"""
