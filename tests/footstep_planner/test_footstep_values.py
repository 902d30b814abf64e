"""Footsteps, stances and plans as values."""

from __future__ import annotations

import math

import numpy as np
import pytest

from door_contract.vocabulary import Foot
from footstep_planner.errors import FootstepPlannerError
from footstep_planner.footstep import Footstep, Pose2D, Stance
from footstep_planner.plan import FootstepPlan, PlanOutcome, PlanResult


def test_nominal_stance_puts_the_left_foot_on_the_left() -> None:
    stance = Stance.nominal(Pose2D(1.0, 2.0, math.pi / 2.0), 0.2)
    assert (stance.left.x, stance.left.y) == pytest.approx((0.9, 2.0))   # facing +y: left is -x
    assert (stance.right.x, stance.right.y) == pytest.approx((1.1, 2.0))
    assert stance.body_pose.x == pytest.approx(1.0)
    assert stance.body_pose.yaw == pytest.approx(math.pi / 2.0)


def test_body_yaw_is_the_circular_mean_of_the_feet() -> None:
    stance = Stance(Footstep(0.0, 0.1, 3.1, Foot.LEFT), Footstep(0.0, -0.1, -3.1, Foot.RIGHT))
    assert abs(abs(stance.body_pose.yaw) - math.pi) < 1e-9


def test_stance_rejects_swapped_feet() -> None:
    left = Footstep(0.0, 0.1, 0.0, Foot.LEFT)
    with pytest.raises(FootstepPlannerError, match="LEFT footstep"):
        Stance(left, left)


def test_stance_centre_and_partner_agree() -> None:
    step = Footstep(0.0, 0.0, 0.3, Foot.RIGHT)
    partner = step.nominal_partner(0.2)
    centre = step.stance_centre(0.2)
    assert partner.foot is Foot.LEFT
    assert Stance(partner, step).body_pose.distance_to(centre) == pytest.approx(0.0, abs=1e-12)


def test_foot_corners_are_counter_clockwise_around_the_sole() -> None:
    corners = Footstep(0.0, 0.0, 0.0, Foot.LEFT).corners(0.22, 0.13)
    expected = np.array([[0.11, 0.065], [-0.11, 0.065], [-0.11, -0.065], [0.11, -0.065]])
    assert np.allclose(corners, expected)


def test_values_are_frozen_and_hashable() -> None:
    step = Footstep(0.0, 0.0, 0.0, Foot.LEFT)
    with pytest.raises(AttributeError):
        step.x = 1.0  # type: ignore[misc]
    assert len({step, Footstep(0.0, 0.0, 0.0, Foot.LEFT)}) == 1


def test_plan_replays_its_stances() -> None:
    start = Stance.nominal(Pose2D(0.0, 0.0, 0.0), 0.2)
    steps = (Footstep(0.3, -0.1, 0.0, Foot.RIGHT), Footstep(0.3, 0.1, 0.0, Foot.LEFT))
    plan = FootstepPlan(start, Pose2D(0.3, 0.0, 0.0), steps, 3.0, 5, 0.001)
    assert plan.final_stance.body_pose.x == pytest.approx(0.3)
    assert len(plan.stances()) == 2
    result = PlanResult(PlanOutcome.SUCCESS, "ok", plan, 5, 0.001)
    assert result.succeeded
    assert not PlanResult(PlanOutcome.UNREACHABLE, "no", None, 0, 0.0).succeeded
