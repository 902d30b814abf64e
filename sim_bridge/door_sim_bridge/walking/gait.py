"""Gait options and the walking pattern: footsteps → CoM/ZMP and swing-foot trajectories.

The pattern is placo's ``WalkPatternGenerator``: a linear inverted pendulum (LIPM) whose ZMP
must stay in each support polygon, solved as one QP over the whole footstep list (a preview
controller in the sense of Kajita et al. 2003: the CoM ``c`` obeys c̈ = ω² (c − z),
ω = √(g / h), h the CoM height, z the ZMP). Swing feet follow smooth curves of height
``foot_height``. A step takes ``single_support_s`` on one foot plus the double support
``double_support_ratio × single_support_s``; the walk starts and ends with a longer double
support (``start_end_ratio``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import placo

from door_contract.converters.footsteps import FootPlacement
from door_contract.vocabulary import Foot
from door_sim_bridge.validation import FieldRange, check_ranges

__all__ = ["GaitOptions", "footstep_sequence", "is_in_place", "placo_parameters", "planar_frame", "smooth_blend"]

SIDE_OF_FOOT = {Foot.LEFT: placo.HumanoidRobot_Side.left, Foot.RIGHT: placo.HumanoidRobot_Side.right}


@dataclass(frozen=True)
class GaitOptions:
    """Timing and shape of the walk (SI units)."""

    single_support_s: float = 0.6  # s on one foot per step
    # double support per step, × single_support_s. 1.5 (a 1.5 s step): walking with 30-45 N
    # pressed sideways at the shoulder and then let go (a leaf sliding along the body, a
    # blocking hand leaving the leaf) fell at 0.5 in 6 of 6 cases and at 1.0 in 2 of 6, and
    # stood at 1.5 in all: a lean against a force that vanishes mid-step is caught on two feet
    double_support_ratio: float = 1.5
    start_end_ratio: float = 2.0  # first and last double support, × the double support
    foot_height: float = 0.05  # m, swing-foot apex
    foot_rise_ratio: float = 0.2  # fraction of the swing spent rising and landing vertically
    zmp_margin: float = 0.02  # m the planned ZMP keeps inside the sole rectangle
    planned_timesteps: int = 500  # LIPM preview horizon in QP steps (≥ the plan's length)
    in_place_tolerance: float = 0.01  # m (and 2× this in rad): a first step this close is dropped
    settle_s: float = 1.0  # s to bring the trunk over the feet when a walk ends or stops
    imu_feedback: bool = True  # orient the model's trunk as measured while walking (damps rocking)

    def __post_init__(self) -> None:
        check_ranges(self, {
            "single_support_s": FieldRange(0.2, 3.0, "s"), "double_support_ratio": FieldRange(0.0, 2.0, ""),
            "start_end_ratio": FieldRange(1.0, 10.0, ""), "foot_height": FieldRange(0.01, 0.2, "m"),
            "foot_rise_ratio": FieldRange(0.0, 0.45, ""), "zmp_margin": FieldRange(0.0, 0.05, "m"),
            "planned_timesteps": FieldRange(50, 5000, "steps"), "in_place_tolerance": FieldRange(0.0, 0.05, "m"),
            "settle_s": FieldRange(0.1, 5.0, "s")})

    @property
    def step_duration_s(self) -> float:
        """Seconds per footstep in the middle of a walk."""
        return self.single_support_s * (1.0 + self.double_support_ratio)


def placo_parameters(gait: GaitOptions, foot_length: float, foot_width: float, feet_spacing: float,
                     com_height: float) -> placo.HumanoidParameters:
    """placo's parameter block for this gait and robot."""
    parameters = placo.HumanoidParameters()
    parameters.single_support_duration = gait.single_support_s
    parameters.single_support_timesteps = 10
    parameters.double_support_ratio = gait.double_support_ratio
    parameters.startend_double_support_ratio = gait.start_end_ratio
    parameters.planned_timesteps = gait.planned_timesteps
    parameters.walk_com_height = com_height
    parameters.walk_foot_height = gait.foot_height
    parameters.walk_trunk_pitch = 0.0
    parameters.walk_foot_rise_ratio = gait.foot_rise_ratio
    parameters.foot_length = foot_length
    parameters.foot_width = foot_width
    parameters.feet_spacing = feet_spacing
    parameters.zmp_margin = gait.zmp_margin
    parameters.walk_max_dtheta = 1.0
    return parameters


def smooth_blend(tau: float) -> float:
    """Cosine ease from 0 to 1 over tau in [0, 1], zero slope at both ends."""
    return 0.5 - 0.5 * math.cos(math.pi * min(max(tau, 0.0), 1.0))


def planar_frame(x: float, y: float, yaw: float) -> np.ndarray:
    """4×4 sole frame on the floor."""
    frame = np.eye(4)
    c, s = math.cos(yaw), math.sin(yaw)
    frame[:2, :2] = [[c, -s], [s, c]]
    frame[:2, 3] = (x, y)
    return frame


def is_in_place(step: FootPlacement, now: np.ndarray, tolerance: float) -> bool:
    """True when ``step`` puts the foot (within ``tolerance``) where it stands (``now``, 4×4)."""
    yaw_now = math.atan2(now[1, 0], now[0, 0])
    turn = math.atan2(math.sin(step.yaw - yaw_now), math.cos(step.yaw - yaw_now))
    return math.hypot(step.x - now[0, 3], step.y - now[1, 3]) <= tolerance and abs(turn) <= 2.0 * tolerance


def footstep_sequence(steps: Sequence[FootPlacement], feet_now: dict[Foot, np.ndarray], tolerance: float,
                      foot_length: float, foot_width: float) -> list[placo.Footstep]:
    """placo footsteps: the two feet where they stand (the first mover first), then the plan.

    A leading step in place (the contract's way to start with the right foot) is dropped:
    it would cost a whole step of lifting a foot and putting it back.
    """
    plan = list(steps)
    if plan and is_in_place(plan[0], feet_now[plan[0].foot], tolerance):
        plan = plan[1:]
    if not plan:
        return []
    first = plan[0].foot
    support = Foot.RIGHT if first is Foot.LEFT else Foot.LEFT
    sequence = [(first, feet_now[first]), (support, feet_now[support])]
    sequence += [(step.foot, planar_frame(step.x, step.y, step.yaw)) for step in plan]
    footsteps = []
    for foot, frame in sequence:
        footstep = placo.Footstep(foot_width, foot_length)
        footstep.side = SIDE_OF_FOOT[foot]
        footstep.frame = frame
        footsteps.append(footstep)
    return footsteps
