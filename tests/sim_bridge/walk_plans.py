"""Footstep plans for the walking tests (straight, turn in place) and how far the soles ended
from them; shared by test_sim_walking.py (TALOS) and test_sim_walking_robots.py."""

from __future__ import annotations

import math

from door_contract.converters.footsteps import FootPlacement
from door_contract.vocabulary import Foot
from door_sim_bridge.world import DoorWorld


def straight_plan(world: DoorWorld, stride: float, steps: int) -> list[FootPlacement]:
    """``steps`` strides of ``stride`` m, then the trailing foot brought alongside."""
    feet = world.foot_placements()
    plan = []
    for index in range(steps + 1):
        foot = Foot.LEFT if index % 2 == 0 else Foot.RIGHT
        advance = stride * min(index + 1, steps)
        plan.append(FootPlacement(foot, feet[foot].x + advance, feet[foot].y, 0.0))
    return plan


def turn_plan(world: DoorWorld, turn: float, pairs: int) -> list[FootPlacement]:
    """Turn in place about the stance centre by ``turn`` rad per pair of steps, from the right
    sole's heading (the first step's stance foot: no step turns more than ``turn`` from the
    sole it leaves, whatever heading error a walk before left between the feet)."""
    feet = world.foot_placements()
    cx, cy = (feet[Foot.LEFT].x + feet[Foot.RIGHT].x) / 2.0, (feet[Foot.LEFT].y + feet[Foot.RIGHT].y) / 2.0
    half = math.hypot(feet[Foot.LEFT].x - feet[Foot.RIGHT].x, feet[Foot.LEFT].y - feet[Foot.RIGHT].y) / 2.0
    plan, yaw = [], feet[Foot.RIGHT].yaw
    for index in range(2 * pairs):
        foot = Foot.LEFT if index % 2 == 0 else Foot.RIGHT
        if foot is Foot.LEFT:
            yaw += turn
        side = 1.0 if foot is Foot.LEFT else -1.0
        plan.append(FootPlacement(foot, cx - side * half * math.sin(yaw), cy + side * half * math.cos(yaw), yaw))
    return plan


def sole_error(world: DoorWorld, plan: list[FootPlacement]) -> tuple[float, float]:
    """Largest position (m) and heading (rad) error of the soles against the plan's last two."""
    feet = world.foot_placements()
    last = {step.foot: step for step in plan[-2:]}
    distance = max(math.hypot(feet[f].x - s.x, feet[f].y - s.y) for f, s in last.items())
    heading = max(abs(math.remainder(feet[f].yaw - s.yaw, math.tau)) for f, s in last.items())
    return distance, heading
