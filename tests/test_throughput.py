"""The faster paths of the studies give the same numbers, bit for bit, as the plain ones.

References: scipy's ``Rotation.from_euler`` for the vectorised vehicle attitude; one block at a
time (the documented stream definition) for the samplers that draw many blocks together.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from sss_locus.experiments.straight_pass import vehicle_attitude


@pytest.mark.parametrize("shape", [(), (1,), (9,), (4, 5), (20_000,)])
def test_vehicle_attitude_is_scipy_from_euler_bit_for_bit(shape):
    rng = np.random.default_rng(len(shape) * 7 + sum(shape))
    yaw, pitch, roll = (rng.uniform(-180, 180, shape), rng.uniform(-90, 90, shape),
                        rng.uniform(-180, 180, shape))
    ours = vehicle_attitude(yaw, pitch, roll)
    ref = Rotation.from_euler("ZYX", np.stack([yaw, -pitch, roll], axis=-1), degrees=True)
    assert ours.single == ref.single
    assert np.array_equal(ours.as_quat(), ref.as_quat())
    assert np.array_equal(ours.as_matrix(), ref.as_matrix())


def test_vehicle_attitude_special_angles_are_scipy_bit_for_bit():
    a = np.array([0.0, -0.0, 90.0, -90.0, 180.0, -180.0, 45.0, 1e-300, 360.0, 720.5])
    for yaw, pitch, roll in ((a, a, a), (a, np.zeros_like(a), -a), (-a, a / 2, np.zeros_like(a))):
        ref = Rotation.from_euler("ZYX", np.stack([yaw, -pitch, roll], axis=-1), degrees=True)
        assert np.array_equal(vehicle_attitude(yaw, pitch, roll).as_matrix(), ref.as_matrix())
