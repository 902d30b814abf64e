"""A pull door's passage in two walks around the tuck: the doorway walk ends ``tuck_at``
before the door plane, and a walk "through" from there plans only the legs that remain."""

from __future__ import annotations

import pytest
from footstep_scenes import collisions_along, door_facing_robot, in_front_of, kinematic_violations, profile_options

from door_contract.vocabulary import DoorOpening, HingeSide, WalkGoal
from footstep_planner.astar import FootstepPlanner
from footstep_planner.footstep import Stance
from footstep_planner.legs import plan_legs
from footstep_planner.pull_passage import PULL_LEG_NAMES
from footstep_planner.requests import GoalSettings, WalkProblem, options_for_problem, walk_problem

SETTINGS = GoalSettings()


def _plan(problem: WalkProblem, goal: WalkGoal, options) -> Stance:
    """Plan ``problem``; assert it is within the limits and clear of wall and posts; its end stance."""
    result = plan_legs(FootstepPlanner(problem.world, options_for_problem(problem, goal, options)),
                       problem.start, problem.legs)
    assert result.succeeded, result.reason
    assert collisions_along(result.plan, problem.world, options) == []
    assert kinematic_violations(result.plan, options) == []
    return result.plan.final_stance


@pytest.mark.parametrize("hinge", list(HingeSide))
@pytest.mark.parametrize("width", [0.80, 0.87, 1.00])
def test_the_doorway_walk_stops_before_the_plane_and_the_walk_on_plans_only_what_remains(
        width: float, hinge: HingeSide) -> None:
    options = profile_options()
    door = door_facing_robot(DoorOpening.PULL, hinge_side=hinge, leaf_width=width, clear_opening=width,
                             handle_offset=0.07).with_angle(0.35)
    stand = walk_problem(WalkGoal.STAND, door, Stance.nominal(in_front_of(door, 2.0), 0.2), options,
                         SETTINGS).legs[0].goal
    start = Stance.nominal(stand, options.nominal_foot_separation)
    doorway = walk_problem(WalkGoal.DOORWAY, door, start, options, SETTINGS)
    assert [leg.name for leg in doorway.legs] == [*PULL_LEG_NAMES[:2], "turn sideways before the doorway",
                                                   "side-step to where the arm tucks"]
    along, before = door.to_door(doorway.legs[-1].goal.x, doorway.legs[-1].goal.y)
    assert before == pytest.approx(SETTINGS.tuck_at) and along == pytest.approx(door.clear_opening / 2.0)
    tucked = _plan(doorway, WalkGoal.DOORWAY, options)
    onward = walk_problem(WalkGoal.THROUGH, door, tucked, options, SETTINGS)
    assert [leg.name for leg in onward.legs] == ["side-step through the doorway", "turn to face away"]
    end = _plan(onward, WalkGoal.THROUGH, options)
    assert door.to_door(end.body_pose.x, end.body_pose.y)[1] < -0.5  # past the wall
    whole = walk_problem(WalkGoal.THROUGH, door, start, options, SETTINGS)
    assert len(whole.legs) == 5  # from the stand pose, "through" is the whole passage


def test_facing_the_doorway_splits_after_the_walk_along_the_wall() -> None:
    options = profile_options()
    facing = GoalSettings.from_parameters({"pull_passage": "facing"})
    door = door_facing_robot(DoorOpening.PULL).with_angle(0.35)
    stand = walk_problem(WalkGoal.STAND, door, Stance.nominal(in_front_of(door, 2.0), 0.2), options,
                         facing).legs[0].goal
    doorway = walk_problem(WalkGoal.DOORWAY, door, Stance.nominal(stand, options.nominal_foot_separation),
                           options, facing)
    assert [leg.name for leg in doorway.legs] == list(PULL_LEG_NAMES[:2])
    onward = walk_problem(WalkGoal.THROUGH, door, _plan(doorway, WalkGoal.DOORWAY, options), options, facing)
    assert [leg.name for leg in onward.legs] == list(PULL_LEG_NAMES[2:])


def test_a_tuck_farther_out_than_the_turn_before_the_doorway_ends_the_walk_at_the_turn() -> None:
    options = profile_options()
    door = door_facing_robot(DoorOpening.PULL).with_angle(0.35)
    far = GoalSettings.from_parameters({"tuck_at": 1.0})
    start = Stance.nominal(in_front_of(door, 0.65), options.nominal_foot_separation)
    doorway = walk_problem(WalkGoal.DOORWAY, door, start, options, far)
    assert doorway.legs[-1].name == "turn sideways before the doorway"
