"""DCM feedback while walking (door_sim_bridge.walking.dcm): the CoM target moves against the
capture point's error from the pattern, the model's offset at the walk's start excepted."""

from __future__ import annotations

import numpy as np
import pytest

from door_sim_bridge.walking.dcm import PATTERN_DEPARTURE, CentreOfMassMotion, DcmFeedback
from door_sim_bridge.walking.stabilizer import StabilizerOptions

OMEGA = 3.34  # 1/s, √(9.81 / 0.88): TALOS's pendulum


def motion(y: float, vy: float) -> CentreOfMassMotion:
    return CentreOfMassMotion(np.array([0.0, y, 0.88]), np.array([0.0, vy, 0.0]))


def test_the_capture_point_is_the_com_plus_its_velocity_over_omega():
    assert motion(0.05, -0.1).dcm(OMEGA) == pytest.approx([0.0, 0.05 - 0.1 / OMEGA])


def test_the_first_error_of_a_walk_is_the_models_offset_and_moves_nothing():
    feedback = DcmFeedback(gain=1.5, limit=0.04)
    planned = motion(0.054, -0.1)
    assert feedback.shift(motion(0.074, -0.1), planned, OMEGA, 0.0) == pytest.approx([0.0, 0.0])  # 2 cm model offset
    assert feedback.shift(motion(0.074, -0.1), planned, OMEGA, 0.0) == pytest.approx([0.0, 0.0])


def test_a_robot_running_off_towards_the_swing_side_is_pulled_back_and_the_pull_is_clipped():
    feedback = DcmFeedback(gain=1.5, limit=0.04)
    planned = motion(0.054, -0.1)
    feedback.shift(planned, planned, OMEGA, 0.0)
    # stop 26's lift-off: the measured CoM 3 mm further out than planned, turning back slower
    shift = feedback.shift(motion(0.057, -0.05), planned, OMEGA, 0.0)
    expected = -1.5 * (0.003 + 0.05 / OMEGA)
    assert shift == pytest.approx([0.0, expected]) and shift[1] < 0.0
    assert feedback.shift(motion(0.12, 0.5), planned, OMEGA, 0.0) == pytest.approx([0.0, -0.04])


def test_a_new_walk_takes_its_own_offset():
    feedback = DcmFeedback(gain=1.0, limit=0.1)
    planned = motion(0.0, 0.0)
    feedback.shift(motion(0.02, 0.0), planned, OMEGA, 0.0)
    feedback.start()
    assert feedback.shift(motion(-0.01, 0.0), planned, OMEGA, 0.0) == pytest.approx([0.0, 0.0])
    assert feedback.shift(motion(0.0, 0.0), planned, OMEGA, 0.0) == pytest.approx([0.0, -0.01])


def test_a_walk_leaves_its_pattern_when_the_capture_point_is_knocked_beyond_the_departure():
    feedback = DcmFeedback(gain=1.0, limit=0.04)
    planned = motion(0.0, 0.0)
    feedback.shift(motion(0.02, 0.0), planned, OMEGA, 0.0)  # the model's 2 cm: not a departure
    feedback.shift(motion(0.02 + 0.9 * PATTERN_DEPARTURE, 0.0), planned, OMEGA, 1.0)
    assert feedback.departure is None
    feedback.shift(motion(0.02, 0.12 * OMEGA), planned, OMEGA, 2.5)  # a blow: 12 cm of capture point
    feedback.shift(motion(0.02, 0.3 * OMEGA), planned, OMEGA, 2.6)  # the first departure is kept
    assert feedback.departure is not None and feedback.departure.walk_time == 2.5
    assert str(feedback.departure) == "the last walk's capture point left its pattern (by 8 cm) 2.5 s into the walk"
    feedback.start()
    assert feedback.departure is None


@pytest.mark.parametrize("field, value", [("dcm_gain", -1.0), ("max_dcm_shift", 0.5)])
def test_the_feedback_options_are_range_checked(field, value):
    from door_sim_bridge.errors import SimulationError

    with pytest.raises(SimulationError, match=field):
        StabilizerOptions(**{field: value})
