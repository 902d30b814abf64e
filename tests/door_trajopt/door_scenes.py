"""Shared scenes for motion-library tests: a sim world at the stand pose and its door estimate
(the scenes of :mod:`door_bringup.passage_rig`, with the tests' defaults)."""

from __future__ import annotations

from door_bringup.passage_rig import NODE_DEFAULTS, perfect_estimate
from door_bringup.passage_rig import motion_setup as rig_motion_setup
from door_bringup.passage_rig import stand_world as rig_stand_world
from door_contract.payloads import DoorEstimate
from door_contract.vocabulary import DoorOpening, HingeSide, Side, grasp_hand
from door_robot.kinematics import RobotKinematics
from door_robot.profile import load_profile
from door_sim_bridge.world import DoorConfig, DoorWorld
from door_trajopt.motions import MotionSetup

estimate_from_world = perfect_estimate
"""A perfect detector: the estimate the detector should publish, from the ground truth."""


def stand_world(opening: DoorOpening = DoorOpening.PUSH, hinge: HingeSide = HingeSide.LEFT,
                **door_fields: float) -> DoorWorld:
    """The robot where the footstep planner node puts it to open this door facing it
    (``door_fields``: other DoorConfig values), for pull doors just past the latch edge and out
    of the pulled leaf: the node's defaults but ``push_passage: facing``, the stance these
    tests were written at (the sideways push stance, the default, has tests of its own)."""
    return rig_stand_world(DoorConfig(opening=opening, hinge_side=hinge, **door_fields),
                           parameters={**NODE_DEFAULTS, "push_passage": "facing"})


def motion_setup(world: DoorWorld, kinematics: RobotKinematics, estimate: DoorEstimate,
                 side: Side | None = None, door_angles: tuple[float, float] = (0.0, 0.0)) -> MotionSetup:
    """The motion-library set-up from the world's measured posture and a door estimate taken
    before the door moved (as the detector's is); by default for the hand that opens it."""
    hand = grasp_hand(estimate.hinge_side, world.config.door.opening) if side is None else side
    return rig_motion_setup(world, kinematics, estimate, hand, door_angles)


def talos_kinematics() -> RobotKinematics:
    return RobotKinematics(load_profile("talos"))
