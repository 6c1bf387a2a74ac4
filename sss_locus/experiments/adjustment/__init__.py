"""The reconstruction chapter's estimator: the joint adjustment of every feature and every pass's
navigation (acoustic bundle adjustment), and the beam-plane constraint in every N-view estimate.

Modules: :mod:`.model` (the inputs: sightings, navigation priors, how a pass's correction moves
its poses), :mod:`.residuals` (weighted residuals and their sparse Jacobian), :mod:`.solver`
(:func:`adjust`, the solver and why it was chosen), :mod:`.covariance` (the Schur complement),
:mod:`.metrics` (horizontal, vertical and map-shape errors).
"""

from .metrics import map_errors
from .model import CORRECTION_NAMES, NavigationPriors, Sightings, corrected_poses
from .residuals import JointProblem
from .solver import DOWNWEIGHT_BELOW, LOSSES, JointAdjustment, adjust

__all__ = ["CORRECTION_NAMES", "DOWNWEIGHT_BELOW", "JointAdjustment", "JointProblem", "LOSSES", "NavigationPriors",
           "Sightings", "adjust", "corrected_poses", "map_errors"]
