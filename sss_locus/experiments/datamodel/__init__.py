"""The data model: the schema of the data files as pydantic v2 models
(:mod:`~sss_locus.experiments.datamodel.models`, built from the sourced value and table of
:mod:`~sss_locus.experiments.datamodel.sourced`)."""

from .models import Data, validate_document
from .sourced import Sourced, validated, validation_message

__all__ = ["Data", "Sourced", "validate_document", "validated", "validation_message"]
