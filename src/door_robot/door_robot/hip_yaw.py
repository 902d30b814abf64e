"""How far a robot may turn per footstep: its hip yaw joints' inward range, read from the model.

A turn in place alternates a toe-out step of the leading foot and a toe-in step of the
trailing one, each up to ``A`` (the profile's ``walking.max_turn``) from the support sole. The
walker's pattern turns the trunk mostly in double support, so when the trailing foot lifts the
trunk still faces the mean of the two stance soles, which differ by up to ``A``; the swing sole
then lands ``A`` past the support sole, ``1.5 A`` inward of the trunk. The hip yaw joint must
turn that far inward:

    1.5 A <= inward range of the hip yaw (from the nominal posture to its limit).

Seen on TALOS (inward range 0.349 rad) with ``A = 0.35`` turning 90° in place beside a door:
both hip yaws reached their limits, the stance foot spun 22° on the floor and the robot fell.

The hip yaw joint of a leg is the joint of the foot's chain, nearest the pelvis, whose axis is
(within :data:`VERTICAL_AXIS_COSINE`) vertical in the nominal posture; "inward" turns the left
foot clockwise seen from above (towards the right foot) and the right foot anticlockwise.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from door_contract.vocabulary import Side
from door_robot.errors import RobotModelError
from door_robot.kinematics import RobotKinematics

__all__ = ["TOE_IN_TRUNK_LAG", "hip_yaw_joint", "inward_hip_yaw_range", "max_turn_of_hips"]

TOE_IN_TRUNK_LAG = 1.5
"""A toe-in step lands this many ``max_turn`` inward of the trunk (module docstring)."""

VERTICAL_AXIS_COSINE = 0.7
"""|cos| between a joint axis and the world's z above which the joint turns the foot in yaw
(G1's hip yaw axis is tilted 27° by its pitched hip in the nominal posture: 0.89)."""


def _leg_chain(kinematics: RobotKinematics, side: Side) -> list[int]:
    """Joint ids from the pelvis down to the ``side`` foot."""
    model = kinematics.model
    joint = model.frames[model.getFrameId(kinematics.profile.feet[side])].parentJoint
    chain = []
    while joint > 0:
        chain.append(joint)
        joint = model.parents[joint]
    return chain[::-1]


def _hip_yaw(kinematics: RobotKinematics, side: Side) -> tuple[int, float]:
    """(joint id, z component of its world axis) of the ``side`` leg's hip yaw joint: the
    first joint from the pelvis with a vertical axis; RobotModelError when there is none."""
    model, data = kinematics.model, kinematics.model.createData()
    pin.computeJointJacobians(model, data, kinematics.nominal_q)
    for joint in _leg_chain(kinematics, side):
        column = model.joints[joint].idx_v
        axis_z = float(pin.getJointJacobian(model, data, joint, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)[5, column])
        if abs(axis_z) >= VERTICAL_AXIS_COSINE:
            return joint, axis_z
    raise RobotModelError(f"{kinematics.profile.name}: the {side.value} leg has no joint with a vertical axis")


def hip_yaw_joint(kinematics: RobotKinematics, side: Side) -> str:
    """Name of the ``side`` leg's hip yaw joint."""
    return str(kinematics.model.names[_hip_yaw(kinematics, side)[0]])


def inward_hip_yaw_range(kinematics: RobotKinematics, side: Side) -> float:
    """How far (rad) the ``side`` hip yaw turns its foot inward from the nominal posture."""
    joint, axis_z = _hip_yaw(kinematics, side)
    index = kinematics.model.joints[joint].idx_q
    nominal = float(kinematics.nominal_q[index])
    lower, upper = float(kinematics.lower_limits[index]), float(kinematics.upper_limits[index])
    # with the axis up a positive angle turns the foot anticlockwise seen from above, which is
    # inward for the right foot
    anticlockwise_is_inward = side is Side.RIGHT
    return upper - nominal if (axis_z > 0.0) == anticlockwise_is_inward else nominal - lower


def max_turn_of_hips(kinematics: RobotKinematics) -> float:
    """The largest ``walking.max_turn`` (rad per step) the hips allow: the smaller inward
    range over both legs divided by :data:`TOE_IN_TRUNK_LAG`."""
    return float(np.min([inward_hip_yaw_range(kinematics, side) for side in kinematics.profile.feet])) / TOE_IN_TRUNK_LAG
