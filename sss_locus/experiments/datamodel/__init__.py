"""The data model: the schema of the data files as pydantic v2 models
(:mod:`~sss_locus.experiments.datamodel.models`)."""

from .models import Data, Sourced, validate_document, validated, validation_message

__all__ = ["Data", "Sourced", "validate_document", "validated", "validation_message"]
