"""The reconstruction chapter's estimator: the joint adjustment of every feature and every pass's
navigation (acoustic bundle adjustment), and the beam-plane constraint in every N-view estimate.

Modules: :mod:`.model` (the inputs: sightings, navigation priors, how a pass's correction moves
its poses), :mod:`.residuals` (weighted residuals and their sparse Jacobian), :mod:`.solver`
(:func:`adjust`, the solver and why it was chosen), :mod:`.covariance` (the Schur complement),
:mod:`.metrics` (horizontal, vertical and map-shape errors), :mod:`.nview` (the per-feature N-view
estimate with the beam-plane constraint, navigation held fixed: :func:`beam_plane_points`).
"""

from .metrics import map_errors
from .nview import BeamPlanePoints, beam_plane_points
from .model import CORRECTION_NAMES, NavigationPriors, Sightings, corrected_poses
from .residuals import JointProblem
from .solver import DOWNWEIGHT_BELOW, LOSSES, JointAdjustment, adjust

__all__ = ["BeamPlanePoints", "CORRECTION_NAMES", "DOWNWEIGHT_BELOW", "JointAdjustment", "JointProblem", "LOSSES", "NavigationPriors",
           "Sightings", "adjust", "beam_plane_points", "corrected_poses", "map_errors"]
