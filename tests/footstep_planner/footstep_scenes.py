"""Shared scenes and independent checks for the footstep planner tests."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from door_contract.vocabulary import DoorOpening, HingeSide
from door_robot.profile import load_profile
from footstep_planner.door import DoorGeometry
from footstep_planner.footprint import body_box_centre
from footstep_planner.footstep import Footstep, Pose2D, Stance
from footstep_planner.geometry import wrap_angle
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.plan import FootstepPlan
from footstep_planner.robot_limits import options_for_walking
from footstep_planner.world import World

DEFAULT_OPTIONS = FootstepPlannerOptions()
SEPARATION = DEFAULT_OPTIONS.nominal_foot_separation
SHRINKS = (1.0, 0.7)
"""The profile's stride and turn as they are, and 30 % shorter (what a physical walker may achieve)."""


def profile_options(shrink: float = 1.0, profile: str = "talos", heuristic_weight: float = 2.5,
                    max_expansions: int = 20_000) -> FootstepPlannerOptions:
    """The node's options for a robot profile, its stride and turn limits scaled by ``shrink``."""
    walking = load_profile(profile).walking
    walking = replace(walking, max_stride=walking.max_stride * shrink, max_turn=walking.max_turn * shrink)
    return options_for_walking(walking, heuristic_weight, max_expansions, 30.0)


def stance_at(x: float, y: float, yaw: float = 0.0) -> Stance:
    """The nominal TALOS stance centred on (x, y, yaw)."""
    return Stance.nominal(Pose2D(x, y, yaw), SEPARATION)


def door_facing_robot(opening: DoorOpening = DoorOpening.PUSH, angle: float = 0.0,
                      hinge_side: HingeSide = HingeSide.LEFT, **dimensions: float) -> DoorGeometry:
    """A door in the wall x = 2 (plane through the hinge), normal pointing to -x, towards a
    robot standing at x < 2 and facing +x; the clear opening is centred on y = 0."""
    opening_width = dimensions.get("clear_opening", 0.87)
    hinge_y = opening_width / 2.0 if hinge_side is HingeSide.LEFT else -opening_width / 2.0
    return DoorGeometry(2.0, hinge_y, math.pi, hinge_side, opening, angle=angle, **dimensions)


def in_front_of(door: DoorGeometry, distance: float) -> Pose2D:
    """The pose ``distance`` m in front of the door plane, centred on the opening, facing it."""
    x, y = door.to_world(door.clear_opening / 2.0, distance)
    return Pose2D(x, y, door.facing_yaw)


def collisions_along(plan: FootstepPlan, world: World,
                     options: FootstepPlannerOptions = DEFAULT_OPTIONS) -> list[str]:
    """Every sole and every double-stance body of the plan that touches an obstacle,
    checked directly with ``World.rectangles_collide`` (not the planner's batch code)."""
    problems = []
    for index, stance in enumerate(plan.stances()):
        step = plan.steps[index]
        if world.rectangles_collide(np.array([step.x]), np.array([step.y]), np.array([step.yaw]),
                                    options.foot_length, options.foot_width,
                                    options.foot_margin)[0]:
            problems.append(f"step {index}: sole {step}")
        body = stance.body_pose
        box_x, box_y = body_box_centre(body.x, body.y, body.yaw, options.body_offset)
        if world.rectangles_collide(np.array([box_x]), np.array([box_y]), np.array([body.yaw]),
                                    2.0 * options.body_half_depth, 2.0 * options.body_half_width,
                                    options.body_margin)[0]:
            problems.append(f"step {index}: body {body}")
    return problems


def kinematic_violations(plan: FootstepPlan,
                         options: FootstepPlannerOptions = DEFAULT_OPTIONS) -> list[str]:
    """Steps that break the step limits relative to the support foot, or cross the legs."""
    problems, stance, tolerance = [], plan.start, 1e-6
    for index, step in enumerate(plan.steps):
        support = stance.foot(step.foot.other)
        forward, lateral, turn = relative_step(support, step)
        if not (-options.max_backward_step - tolerance <= forward
                <= options.max_stride + tolerance):
            problems.append(f"step {index}: forward offset {forward:.3f}")
        if not (options.min_foot_separation - tolerance <= lateral
                <= options.max_stance_separation + tolerance):
            problems.append(f"step {index}: lateral offset {lateral:.3f}")
        if abs(turn) > options.max_turn + tolerance:
            problems.append(f"step {index}: turn {turn:.3f}")
        stance = stance.with_footstep(step)
    return problems


def relative_step(support: Footstep, step: Footstep) -> tuple[float, float, float]:
    """(forward, lateral to its own side, yaw change) of ``step`` in ``support``'s frame."""
    dx, dy = step.x - support.x, step.y - support.y
    cos_yaw, sin_yaw = math.cos(support.yaw), math.sin(support.yaw)
    forward = cos_yaw * dx + sin_yaw * dy
    left = -sin_yaw * dx + cos_yaw * dy
    return forward, step.foot.sign * left, wrap_angle(step.yaw - support.yaw)


def alternates(plan: FootstepPlan) -> bool:
    """Consecutive steps move different feet."""
    return all(a.foot is not b.foot for a, b in zip(plan.steps, plan.steps[1:]))
