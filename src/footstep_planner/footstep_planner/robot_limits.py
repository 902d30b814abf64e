"""The planner's options from a robot profile: its walking limits and body extents.

Robot-agnostic: every limit and dimension comes from the profile (``params/robot_*.yaml``,
:class:`door_robot.profile.WalkingLimits`); the planner keeps a margin inside the step
limits because the walking controller checks its own.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from door_robot.profile import WalkingLimits, load_profile
from footstep_planner.options import FootstepPlannerOptions

__all__ = ["STEP_LIMIT_MARGIN", "options_for_walking", "planner_options"]

STEP_LIMIT_MARGIN = 0.95
"""Plan within 95 % of the robot's stride, side step and turn: the robot checks its own."""
MIN_FOOT_SEPARATION = 0.16
"""Legs no closer than this (m), or 90 % of the profile's separation when that is less."""


def options_for_walking(walking: WalkingLimits, heuristic_weight: float, max_expansions: int,
                        max_planning_time: float) -> FootstepPlannerOptions:
    """Planner options from a robot's walking limits and the search settings."""
    return FootstepPlannerOptions(
        max_stride=walking.max_stride * STEP_LIMIT_MARGIN,
        max_side_step=walking.max_side_step * STEP_LIMIT_MARGIN,
        max_turn=walking.max_turn * STEP_LIMIT_MARGIN,
        nominal_foot_separation=walking.foot_separation,
        min_foot_separation=min(MIN_FOOT_SEPARATION, walking.foot_separation * 0.9),
        foot_length=walking.foot_length, foot_width=walking.foot_width,
        body_half_width=walking.body_width / 2.0, body_half_depth=walking.body_depth / 2.0,
        body_offset=walking.body_offset,
        heuristic_weight=heuristic_weight, max_expansions=max_expansions,
        max_planning_time=max_planning_time)


def planner_options(profile_name: str, parameters: Mapping[str, Any]) -> FootstepPlannerOptions:
    """:func:`options_for_walking` for a profile name and the node's search parameters
    (``heuristic_weight``, ``max_expansions``, ``max_planning_time``)."""
    return options_for_walking(load_profile(profile_name).walking, parameters["heuristic_weight"],
                               parameters["max_expansions"], parameters["max_planning_time"])
