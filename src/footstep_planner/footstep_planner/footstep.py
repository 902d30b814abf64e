"""Footsteps and stances in the plane.

All poses are in the ``odom`` frame, SI units, REP-103 axes (x forward,
y left, z up); ``yaw`` is the heading about z in radians.  A foot pose is the
centre of the sole rectangle; the sole's long side points along the foot's yaw.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from door_contract.vocabulary import Foot
from footstep_planner.errors import FootstepPlannerError
from footstep_planner.geometry import FloatArray, rectangle_corners, wrap_angle

__all__ = ["Footstep", "Pose2D", "Stance", "foot_corners"]


@dataclass(frozen=True)
class Pose2D:
    """A planar pose: position (m) and yaw (rad) in ``odom``."""

    x: float
    y: float
    yaw: float

    def is_finite(self) -> bool:
        """True when no coordinate is NaN or infinite."""
        return all(math.isfinite(v) for v in (self.x, self.y, self.yaw))

    def transform(self, forward: float, left: float) -> tuple[float, float]:
        """The point ``(forward, left)`` of this pose's frame, in ``odom``."""
        cos_yaw, sin_yaw = math.cos(self.yaw), math.sin(self.yaw)
        return (self.x + cos_yaw * forward - sin_yaw * left,
                self.y + sin_yaw * forward + cos_yaw * left)

    def distance_to(self, other: Pose2D) -> float:
        """Euclidean distance between the two positions (m)."""
        return math.hypot(other.x - self.x, other.y - self.y)

    def yaw_difference(self, other: Pose2D) -> float:
        """|other.yaw - self.yaw| wrapped to [0, pi] (rad)."""
        return abs(wrap_angle(other.yaw - self.yaw))


@dataclass(frozen=True)
class Footstep:
    """Where one foot is placed: sole centre (m), yaw (rad) and which foot."""

    x: float
    y: float
    yaw: float
    foot: Foot

    @property
    def pose(self) -> Pose2D:
        """The sole-centre pose."""
        return Pose2D(self.x, self.y, self.yaw)

    def is_finite(self) -> bool:
        """True when no coordinate is NaN or infinite."""
        return self.pose.is_finite()

    def corners(self, foot_length: float, foot_width: float) -> FloatArray:
        """The sole rectangle's 4 corners, counter-clockwise, shape (4, 2)."""
        return foot_corners(self, foot_length, foot_width)

    def nominal_partner(self, separation: float) -> Footstep:
        """The other foot beside this one, parallel, ``separation`` m apart (centre to centre)."""
        x, y = self.pose.transform(0.0, -self.foot.sign * separation)
        return Footstep(x, y, self.yaw, self.foot.other)

    def stance_centre(self, separation: float) -> Pose2D:
        """Body pose of the nominal stance on this foot: half a separation towards the other foot.

        This point, c(F) in the planner's maths, is where the body stands when
        this foot supports and the other is placed in the nominal stance.
        """
        x, y = self.pose.transform(0.0, -self.foot.sign * separation / 2.0)
        return Pose2D(x, y, self.yaw)


@dataclass(frozen=True)
class Stance:
    """Both feet on the ground."""

    left: Footstep
    right: Footstep

    def __post_init__(self) -> None:
        if self.left.foot is not Foot.LEFT or self.right.foot is not Foot.RIGHT:
            raise FootstepPlannerError("Stance needs a LEFT footstep as left and a RIGHT footstep as right")

    @classmethod
    def nominal(cls, body: Pose2D, separation: float) -> Stance:
        """Feet parallel, ``separation`` m apart, centred on ``body`` and facing its yaw."""
        left_x, left_y = body.transform(0.0, separation / 2.0)
        right_x, right_y = body.transform(0.0, -separation / 2.0)
        return cls(Footstep(left_x, left_y, body.yaw, Foot.LEFT),
                   Footstep(right_x, right_y, body.yaw, Foot.RIGHT))

    def foot(self, which: Foot) -> Footstep:
        """The footstep of foot ``which``."""
        return self.left if which is Foot.LEFT else self.right

    def with_footstep(self, step: Footstep) -> Stance:
        """This stance after placing ``step`` (it replaces the same foot)."""
        if step.foot is Foot.LEFT:
            return Stance(step, self.right)
        return Stance(self.left, step)

    @property
    def body_pose(self) -> Pose2D:
        """Body pose of the stance: midpoint of the soles, circular mean of their yaws."""
        yaw = self.left.yaw + wrap_angle(self.right.yaw - self.left.yaw) / 2.0
        return Pose2D((self.left.x + self.right.x) / 2.0, (self.left.y + self.right.y) / 2.0,
                      wrap_angle(yaw))

    def is_finite(self) -> bool:
        """True when both footsteps are finite."""
        return self.left.is_finite() and self.right.is_finite()


def foot_corners(step: Footstep, foot_length: float, foot_width: float) -> FloatArray:
    """Sole rectangle corners of ``step`` (counter-clockwise), shape (4, 2)."""
    corners = rectangle_corners(np.array([step.x]), np.array([step.y]), np.array([step.yaw]),
                                foot_length / 2.0, foot_width / 2.0)
    sole: FloatArray = corners[0]
    return sole
