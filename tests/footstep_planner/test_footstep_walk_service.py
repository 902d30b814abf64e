"""How the footstep planner serves a request, without ROS: a plan is proposed (even index = left
foot, markers, a stamp after the last) and answered SUCCESS with its figures, and the next
request starts where it left the feet; a failed search, bad input, a bug and a superseded
request each get their answer; a push passage says when the door angle it plans for changed."""

from __future__ import annotations

import math

import numpy as np
import pytest
from footstep_scenes import profile_options
from test_footstep_proposal import _door

from door_contract.payloads import FootstepFigures, FootstepRequest, OutcomeStatus, PlanningOutcome, decode, encode
from door_contract.planner_service import Finished
from door_contract.vocabulary import DoorOpening, Foot, WalkGoal
from footstep_planner.errors import NoWalkForDoor, RequestRefused
from footstep_planner.requests import GoalSettings
from footstep_planner.walk_service import Answer, WalkService


def _service() -> WalkService:
    return WalkService(profile_options(), GoalSettings())


def _request(request_id: int = 7, goal: WalkGoal = WalkGoal.STAND, door_angle: float = 0.0) -> FootstepRequest:
    return FootstepRequest(request_id, goal, DoorOpening.PUSH, door_angle=door_angle)


def _planned(service: WalkService, request: FootstepRequest, base: np.ndarray | None = None,
             now_ns: int = 1_000) -> Answer:
    """Solve ``request`` from ``base`` (default: the origin) and answer it, as the node does."""
    snapshot = service.snapshot(np.eye(4) if base is None else base, None, _door())
    return service.answer(Finished(request, result=service.solve(request, snapshot)), now_ns)


def test_a_plan_is_proposed_and_answered_with_its_figures_and_the_next_starts_where_it_ends() -> None:
    service = _service()
    answer = _planned(service, _request(), now_ns=5_000)
    assert answer.status is OutcomeStatus.SUCCESS and answer.reason == "" and not answer.bug
    assert [f.foot for f in answer.footsteps] == [Foot.LEFT if i % 2 == 0 else Foot.RIGHT
                                                  for i in range(len(answer.footsteps))]
    assert len(answer.shapes) == len(answer.footsteps)
    assert answer.stamp_ns == 5_000 and answer.outcome(7).stamp_ns == 5_000
    figures = answer.outcome(7).footsteps
    assert figures is not None and figures.steps > 0 and 1.0 < figures.length_m < 2.5
    assert service.planned_stance is not None
    stance = service.planned_stance
    base = np.eye(4)
    base[:2, 3] = stance.body_pose.x, stance.body_pose.y
    base[:2, :2] = [[math.cos(stance.body_pose.yaw), -math.sin(stance.body_pose.yaw)],
                    [math.sin(stance.body_pose.yaw), math.cos(stance.body_pose.yaw)]]
    assert service.snapshot(base, None, _door()).planned_stance is stance  # the next request starts there
    again = _planned(service, _request(8), base, now_ns=5_000)  # the clock has not advanced
    assert again.stamp_ns == 5_001  # still a stamp of its own


def test_a_failed_search_is_a_failure_with_the_planners_outcome_and_proposes_nothing() -> None:
    service = _service()
    behind_the_wall = np.eye(4)
    behind_the_wall[0, 3] = 2.5  # the base inside the wall's plane: no start to plan from
    answer = _planned(service, _request(), behind_the_wall)
    assert answer.status is OutcomeStatus.FAILURE and answer.footsteps == () and answer.stamp_ns == -1
    assert answer.reason.startswith("invalid_start: start stance collides") and not answer.bug
    assert answer.figures == FootstepFigures(0) and answer.outcome(7).stamp_ns == -1
    assert service.planned_stance is None


def test_bad_input_a_bug_and_a_superseded_request_are_answered_without_a_proposal() -> None:
    service = _service()
    refused = service.answer(Finished(_request(), error=RequestRefused("no valid odometry yet")), 0)
    assert (refused.status, refused.reason, refused.bug) == (OutcomeStatus.REJECTED, "no valid odometry yet", "")
    crashed = service.answer(Finished(_request(), error=ZeroDivisionError("division by zero")), 0)
    assert crashed.status is OutcomeStatus.FAILURE and crashed.reason.startswith("internal error")
    assert crashed.bug == "ZeroDivisionError('division by zero')"
    superseded = service.answer(Finished(_request(), dropped="superseded by request 8"), 0)
    assert (superseded.status, superseded.reason) == (OutcomeStatus.SUPERSEDED, "superseded by request 8")
    assert not (refused.footsteps or crashed.footsteps or superseded.footsteps)


def test_a_push_passage_says_when_the_door_angle_it_plans_for_changed() -> None:
    service = _service()
    snapshot = service.snapshot(np.eye(4), None, _door())
    first = service.solve(_request(1, WalkGoal.THROUGH, door_angle=0.0), snapshot)
    assert first.angle_change is None and service.passage_angle == GoalSettings().passage_door_angle
    same = service.solve(_request(2, WalkGoal.THROUGH, door_angle=1.0), snapshot)  # still pushed to 1.57 rad
    assert same.angle_change is None
    wider = service.solve(_request(3, WalkGoal.THROUGH, door_angle=1.9), snapshot)
    assert wider.angle_change == (GoalSettings().passage_door_angle, 1.9)
    assert wider.problem.door.angle == 1.9


def test_an_outcome_carries_the_searchs_figures_and_decodes_as_it_went_out() -> None:
    outcome = Answer(OutcomeStatus.FAILURE, "no_path: budget spent", 0.5, FootstepFigures(1_200)).outcome(3)
    assert (outcome.request_id, outcome.status, outcome.footsteps) == (3, OutcomeStatus.FAILURE, FootstepFigures(1_200))
    assert outcome.motion is None and outcome.door_angle is None
    assert decode(PlanningOutcome, encode(outcome)) == outcome


def test_a_doorway_walk_the_door_does_not_have_is_answered_skipped_and_one_it_has_is_planned() -> None:
    """A push door narrower than push_tuck_min_width has no doorway walk: SKIPPED with the
    planner's reason, nothing proposed, and the outcome says so on the bus; at the default
    width threshold the same 0.9 m door's doorway walk is planned (to the side-step line first)."""
    narrow = WalkService(profile_options(), GoalSettings(push_tuck_min_width=0.95))
    request = _request(goal=WalkGoal.DOORWAY)
    with pytest.raises(NoWalkForDoor) as raised:  # on the worker thread, which hands it over in a Finished
        narrow.solve(request, narrow.snapshot(np.eye(4), None, _door()))
    skipped = narrow.answer(Finished(request, error=raised.value), 1_000)
    assert skipped.status is OutcomeStatus.SKIPPED and "push_tuck_min_width" in skipped.reason
    assert not skipped.footsteps and skipped.stamp_ns == -1 and not skipped.bug
    assert decode(PlanningOutcome, encode(skipped.outcome(7))).status is OutcomeStatus.SKIPPED
    assert narrow.planned_stance is None
    wide = _planned(_service(), _request(goal=WalkGoal.DOORWAY))
    assert wide.status is OutcomeStatus.SUCCESS and wide.footsteps, wide.reason
