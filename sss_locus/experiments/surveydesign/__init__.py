"""New code of the survey-design chapter, as its subpackage (the chapter's older modules stay
flat: ``survey_area``, ``survey_lines``, ``survey_coverage``, ``survey_objectives``,
``survey_plans``, ``survey_design``):

- :mod:`.turns`: U-turns of the platform's turn radius as points on the path;
- :mod:`.route`: the whole track (turns, transits inside the fence and around holes) and the
  fences;
- :mod:`.joint`: a plan's segments flown as passes with the per-pass navigation noise and its
  features and navigation adjusted jointly (the reconstruction chapter's joint adjustment);
- :mod:`.scoring`: plans scored with it over independent seeds, with intervals, and the
  recommendation that holds against them.

Frames: the local frame of :mod:`sss_locus.experiments.survey_area` (``x`` east, ``y`` north,
metres); headings of the line tables are degrees counter-clockwise from east (as in
:mod:`sss_locus.experiments.survey_lines`).
"""
