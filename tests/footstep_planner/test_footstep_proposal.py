"""The footstep planner's request → problem → proposal path without ROS: refusals name what is
missing, the plan goes out even index = left foot, its markers are sole-sized boxes per foot."""

from __future__ import annotations

import math

import numpy as np
import pytest
from footstep_scenes import profile_options

from door_contract.converters.markers import shapes_to_marker_array
from door_contract.payloads import DoorEstimate, FootstepRequest
from door_contract.vocabulary import DoorOpening, Foot, HingeSide, WalkGoal
from footstep_planner.errors import FootstepPlannerError, RequestRefused
from footstep_planner.footstep import Footstep, Pose2D, Stance
from footstep_planner.plan import FootstepPlan
from footstep_planner.proposal import FOOT_COLOURS, contract_footsteps, footstep_shapes, walked_length
from footstep_planner.requests import (
    GoalSettings,
    Snapshot,
    WalkPlanners,
    options_for_problem,
    problem_for_request,
)

START = Stance(Footstep(0.0, 0.1, 0.0, Foot.LEFT), Footstep(0.0, -0.1, 0.0, Foot.RIGHT))
SETTINGS = GoalSettings()


def _plan(*steps: Footstep) -> FootstepPlan:
    return FootstepPlan(START, Pose2D(0.4, 0.0, 0.0), tuple(steps), 1.0, 3, 0.01)


def _door(normal: tuple[float, float, float] = (-1.0, 0.0, 0.0)) -> DoorEstimate:
    """A closed 0.9 m door in the wall x = 2.5, handle on the right seen from the robot at the origin."""
    corners = ((2.5, 0.45, 0.0), (2.5, -0.45, 0.0), (2.5, -0.45, 2.0), (2.5, 0.45, 2.0))
    return DoorEstimate(1.0, "odom", (2.45, -0.37, 1.0), normal, HingeSide.LEFT, 0.9, corners, 1.0, 10, "automatic")


def _request(goal: WalkGoal = WalkGoal.STAND, door_stamp: float = -1.0) -> FootstepRequest:
    return FootstepRequest(7, goal, DoorOpening.PUSH, door_stamp=door_stamp)


def test_a_plan_starting_with_the_right_foot_steps_in_place_with_the_left_first() -> None:
    right_first = _plan(Footstep(0.2, -0.1, 0.0, Foot.RIGHT), Footstep(0.4, 0.1, 0.0, Foot.LEFT))
    placements = contract_footsteps(START, right_first)
    assert [p.foot for p in placements] == [Foot.LEFT, Foot.RIGHT, Foot.LEFT]
    assert (placements[0].x, placements[0].y) == (0.0, 0.1)                   # the left foot where it stands
    left_first = contract_footsteps(START, _plan(Footstep(0.2, 0.1, 0.0, Foot.LEFT)))
    assert [(p.foot, p.x) for p in left_first] == [(Foot.LEFT, 0.2)]


def test_footstep_markers_are_sole_sized_boxes_coloured_by_foot() -> None:
    placements = contract_footsteps(START, _plan(Footstep(0.2, -0.1, 0.5, Foot.RIGHT)))
    shapes = footstep_shapes(placements, 0.21, 0.13)
    assert [s.marker_id for s in shapes] == [0, 1] and [s.rgba for s in shapes] == [FOOT_COLOURS[Foot.LEFT],
                                                                                  FOOT_COLOURS[Foot.RIGHT]]
    markers = shapes_to_marker_array(shapes).markers
    assert len(markers) == 3 and markers[0].action == markers[0].DELETEALL
    right = markers[2]
    assert right.type == right.CUBE and right.ns == "footsteps" and right.header.frame_id == "odom"
    assert (right.scale.x, right.scale.y, right.scale.z) == pytest.approx((0.21, 0.13, 0.02))
    assert (right.pose.position.x, right.pose.position.y, right.pose.position.z) == pytest.approx((0.2, -0.1, 0.01))
    assert abs(right.pose.orientation.z) == pytest.approx(math.sin(0.25))
    assert abs(right.pose.orientation.w) == pytest.approx(math.cos(0.25))


def test_walked_length_is_from_the_middle_of_the_start_stance() -> None:
    assert walked_length(START, Pose2D(3.0, 4.0, 0.0)) == pytest.approx(5.0)


@pytest.mark.parametrize("snapshot, reason", [
    (Snapshot(None, None, _door(), None), "no valid odometry yet"),
    (Snapshot(np.eye(4), None, None, None), "no door estimate yet"),
    (Snapshot(np.eye(4), None, _door((0.0, 0.0, 1.0)), None), "not horizontal"),
])
def test_a_request_without_usable_inputs_is_refused_with_the_reason(snapshot: Snapshot, reason: str) -> None:
    options = profile_options()
    with pytest.raises(RequestRefused, match=reason) as refused:
        problem_for_request(_request(), snapshot, options, SETTINGS)
    assert isinstance(refused.value, FootstepPlannerError) and not isinstance(refused.value, ValueError)


def test_a_named_estimate_that_never_arrived_is_refused_by_its_stamp() -> None:
    with pytest.raises(RequestRefused, match="stamp 4.250 s was not received"):
        problem_for_request(_request(door_stamp=4.25), Snapshot(np.eye(4), None, None, None),
                            profile_options(), SETTINGS)


def test_a_stand_request_is_planned_from_the_nominal_stance_around_the_base() -> None:
    options = profile_options()
    problem = problem_for_request(_request(), Snapshot(np.eye(4), None, _door(), None), options, SETTINGS)
    assert problem.start.body_pose.distance_to(Pose2D(0.0, 0.0, 0.0)) < 1e-9
    assert len(problem.legs) == 1 and problem.legs[0].goal.x < 2.5
    result, relaxed_from = WalkPlanners().plan(problem, options_for_problem(problem, WalkGoal.STAND, options))
    assert result.succeeded and relaxed_from == ""
    placements = contract_footsteps(problem.start, result.plan)
    assert all(p.foot is (Foot.LEFT if i % 2 == 0 else Foot.RIGHT) for i, p in enumerate(placements))
