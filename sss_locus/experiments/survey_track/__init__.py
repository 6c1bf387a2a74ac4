"""The track a vehicle flies through a survey plan (the survey-design chapter's subpackage for
new code): turns of the platform's radius (:mod:`.turns`), transit legs that stay inside the
fence and around holes, and the fences themselves (:mod:`.route`).

Frames: the local frame of :mod:`sss_locus.experiments.survey_area` (``x`` east, ``y`` north,
metres); headings of the line tables are degrees counter-clockwise from east (as in
:mod:`sss_locus.experiments.survey_lines`).
"""
