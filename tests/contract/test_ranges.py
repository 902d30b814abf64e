"""One range check for every package's options (door_contract.ranges.check_in_range): the same
wording everywhere, each package's own error type."""

import math

import pytest

from door_contract.ranges import FieldRange, check_in_range
from door_detection.errors import DetectionError
from door_detection.options import DetectionOptions
from door_sim_bridge.errors import SimulationError
from door_sim_bridge.world import CameraConfig
from door_trajopt.motions import MotionOptions
from door_trajopt.problem import TrajoptError
from footstep_planner.errors import FootstepPlannerError
from footstep_planner.options import FootstepPlannerOptions


class OptionError(Exception):
    pass


@pytest.mark.parametrize("value, words", [
    (2.0, "push_angle = 2.0 is outside the allowed range (0, 1] rad"),
    (0.0, "push_angle = 0.0 is outside the allowed range (0, 1] rad"),
    (math.nan, "push_angle = nan is outside"),
    (True, "push_angle must be a number in (0, 1] rad, got True"),
    ("0.5", "push_angle must be a number in (0, 1] rad, got '0.5'"),
])
def test_a_value_outside_its_interval_or_not_a_number_is_refused_in_words(value, words):
    with pytest.raises(OptionError, match=words.replace("(", r"\(").replace("[", r"\[")):
        check_in_range("push_angle", value, FieldRange(0.0, 1.0, "rad", low_open=True), OptionError)


def test_an_integer_field_refuses_a_float_and_admits_its_ends():
    with pytest.raises(OptionError, match="must be an integer in"):
        check_in_range("waypoints", 4.0, FieldRange(4, 200, ""), OptionError, integer=True)
    check_in_range("waypoints", 4, FieldRange(4, 200, ""), OptionError, integer=True)
    check_in_range("waypoints", 200, FieldRange(4, 200, ""), OptionError, integer=True)


@pytest.mark.parametrize("build, error, label", [
    (lambda: MotionOptions(push_angle=-1.0), TrajoptError, "MotionOptions.push_angle"),
    (lambda: DetectionOptions(canny_low=0), DetectionError, "canny_low"),
    (lambda: CameraConfig(near=-1.0), SimulationError, "CameraConfig.near"),
    (lambda: FootstepPlannerOptions(max_stride=-1.0), FootstepPlannerError, "max_stride"),
])
def test_every_package_words_it_the_same_and_raises_its_own_error(build, error, label):
    with pytest.raises(error, match=rf"{label} = -?[0-9.]+ is outside the allowed range [\[(]"):
        build()
