"""The action set: kinematically valid, mirrored, never crossing the legs."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from footstep_scenes import profile_options

from door_contract.vocabulary import Foot
from footstep_planner.actions import (
    CLEARANCE_STEP,
    CLOSING_STEP,
    ActionSet,
    StepAction,
    cleared_turn,
    is_kinematically_valid,
)
from footstep_planner.geometry import rectangle_corners
from footstep_planner.obstacles import Obstacle
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.world import World

OPTIONS = FootstepPlannerOptions()
ACTIONS = ActionSet.from_options(OPTIONS)


def test_action_set_has_forward_backward_side_and_turning_steps() -> None:
    actions = ACTIONS.actions
    assert CLOSING_STEP in actions
    assert max(a.forward for a in actions) == pytest.approx(OPTIONS.max_stride)
    assert min(a.forward for a in actions) == pytest.approx(-OPTIONS.max_backward_step)
    assert max(a.outward for a in actions) == pytest.approx(OPTIONS.max_side_step)
    assert max(abs(a.turn) for a in actions) == pytest.approx(OPTIONS.max_turn)
    assert 20 <= len(actions) <= 40


@pytest.mark.parametrize("swing", list(Foot))
def test_every_action_lands_on_its_own_side_within_the_limits(swing: Foot) -> None:
    table = ACTIONS.tables[swing]
    forward, left, yaw = table.foot.T
    lateral = swing.sign * left
    assert np.all(forward <= OPTIONS.max_stride + 1e-9)
    assert np.all(forward >= -OPTIONS.max_backward_step - 1e-9)
    assert np.all(lateral >= OPTIONS.min_foot_separation - 1e-9)  # no leg crossing
    assert np.all(lateral <= OPTIONS.max_stance_separation + 1e-9)
    assert np.all(np.abs(yaw) <= OPTIONS.max_turn + 1e-9)


def test_soles_never_overlap() -> None:
    support = Obstacle("support", tuple(map(tuple, rectangle_corners(
        np.zeros(1), np.zeros(1), np.zeros(1), OPTIONS.foot_length / 2,
        OPTIONS.foot_width / 2)[0])))
    for swing in Foot:
        table = ACTIONS.tables[swing]
        overlap = World((support,)).rectangles_collide(*table.foot.T, OPTIONS.foot_length,
                                                       OPTIONS.foot_width)
        assert not overlap.any()


def test_right_foot_actions_mirror_the_left() -> None:
    left, right = ACTIONS.tables[Foot.LEFT], ACTIONS.tables[Foot.RIGHT]
    assert np.allclose(left.foot * [1, -1, -1], right.foot)
    assert np.allclose(left.cost, right.cost)


def test_closing_step_is_the_nominal_stance() -> None:
    x, y, yaw = CLOSING_STEP.swing_offset(Foot.RIGHT, OPTIONS.nominal_foot_separation)
    assert (x, y, yaw) == pytest.approx((0.0, -OPTIONS.nominal_foot_separation, 0.0))


def test_turn_in_place_keeps_the_stance_centre() -> None:
    turn = StepAction(0.0, 0.0, OPTIONS.max_turn)
    separation = OPTIONS.nominal_foot_separation
    x, y, yaw = turn.swing_offset(Foot.LEFT, separation)
    # centre of the new stance = swing foot shifted half a separation to its right
    centre = (x + math.sin(yaw) * separation / 2, y - math.cos(yaw) * separation / 2)
    assert centre == pytest.approx((0.0, separation / 2))


def test_invalid_actions_are_filtered() -> None:
    assert not is_kinematically_valid(StepAction(0.5, 0.0, 0.0), OPTIONS)   # too long
    assert not is_kinematically_valid(StepAction(0.0, -0.1, 0.0), OPTIONS)  # crosses legs
    assert not is_kinematically_valid(StepAction(0.0, 0.0, 0.6), OPTIONS)   # turns too far
    assert is_kinematically_valid(StepAction(0.3, 0.0, 0.0), OPTIONS)


def test_action_set_scales_with_the_options() -> None:
    short = ActionSet.from_options(FootstepPlannerOptions(max_stride=0.2, max_turn=0.2))
    assert max(a.forward for a in short.actions) == pytest.approx(0.2)
    assert short.max_turn == pytest.approx(0.2)


@pytest.mark.parametrize("shrink", [1.0, 0.7])
def test_full_turns_clear_the_support_sole_with_talos_soles_close_together(shrink: float) -> None:
    """TALOS stands with its 0.13 m soles 0.17 m apart: a full turn in place about the sole's
    centre swings the heel (toe-out) or the toe (toe-in) into the support sole's margin. The
    turns move outward just enough, so the full turn exists in place and walking, both ways."""
    options = profile_options(shrink)
    actions = ActionSet.from_options(options).actions
    full = [a for a in actions if abs(a.turn) == pytest.approx(options.max_turn)]
    in_place_and_walking, both_ways = {True, False}, {True, False}
    assert {(a.forward == 0.0, a.turn > 0.0) for a in full} == {(p, w) for p in in_place_and_walking for w in both_ways}
    for action in full:
        assert is_kinematically_valid(action, options)
        assert 0.0 <= action.outward <= options.max_side_step
        tighter = StepAction(action.forward, action.outward - CLEARANCE_STEP, action.turn)
        assert action.outward == 0.0 or not is_kinematically_valid(tighter, options)  # the least shift


def test_a_turn_that_no_shift_can_clear_is_dropped() -> None:
    options = profile_options()
    crossing = StepAction(-options.max_backward_step, 0.0, options.max_turn)
    assert cleared_turn(replace(crossing, outward=-0.2), replace(options, max_side_step=0.0)) is None
