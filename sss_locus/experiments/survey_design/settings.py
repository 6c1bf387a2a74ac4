"""The survey-design chapter's settings: the ``[survey_design]`` table of the run's data
(``data/survey_design.toml`` merged with the user's files and ``--set`` overrides), validated by
the data model (:class:`~sss_locus.experiments.datamodel.models.SurveyDesign`). Read by the plans
and by the area reader (the wall clearance of an area file that gives none)."""

from __future__ import annotations

from sss_locus.experiments.datamodel import datadoc
from sss_locus.experiments.datamodel import models


def load_settings(doc=None) -> dict:
    """The ``survey_design`` table (``data/survey_design.toml`` merged with the active user data,
    or of ``doc``), validated: values by key plus ``provenance`` (key -> source/assumption).

    Parameters
    ----------
    doc : dict or None
        A data document (parsed TOML tables); ``None`` reads ``data/survey_design.toml`` merged
        with the active user data.

    Returns
    -------
    dict
        Setting name -> value (units in the names: ``_m``, ``_deg``, fractions) plus
        ``provenance`` (key -> source or assumption).

    Raises
    ------
    ValueError
        The table fails validation (named key and valid range).
    """
    table = datadoc.load_table(lambda d: models.validate_document(d, ("survey_design",)), None, "survey_design",
                               doc=doc).survey_design
    return {**models.values(table), "provenance": models.provenance(table, "survey_design")}
