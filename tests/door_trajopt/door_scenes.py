"""Shared scenes for motion-library tests: a sim world at the stand pose and its door estimate."""

from __future__ import annotations

import numpy as np

from door_contract.payloads import DoorEstimate, HingeSide
from door_robot.kinematics import RobotKinematics
from door_robot.profile import Side, load_profile
from door_sim_bridge.world import DoorConfig, DoorOpening, DoorWorld, StanceConfig, WorldConfig
from door_sim_bridge.world import HingeSide as SimHingeSide
from door_trajopt.chain import ArmChain
from door_trajopt.door_model import door_model_from_estimate
from door_trajopt.motions import MotionSetup, support_polygon


def estimate_from_world(world: DoorWorld) -> DoorEstimate:
    """A perfect detector: the estimate the detector should publish, from the ground truth."""
    truth = world.door_ground_truth()
    hinge = HingeSide.LEFT if world.config.door.hinge_side is SimHingeSide.LEFT else HingeSide.RIGHT
    return DoorEstimate(world.time, "odom", tuple(truth.handle_grasp_pose[:3, 3]), tuple(truth.normal), hinge,
                        truth.width, tuple(tuple(c) for c in truth.corners), 1.0, 10, "automatic")


def stand_world(opening: DoorOpening = DoorOpening.PUSH, hinge: SimHingeSide = SimHingeSide.LEFT,
                reach: float = 0.5, handle_offset: float = 0.2) -> DoorWorld:
    """The robot facing the door ``reach`` m from its plane, ``handle_offset`` m to the hinge
    side of the handle (the footstep planner's stand pose)."""
    door = DoorConfig(opening=opening, hinge_side=hinge)
    probe = DoorWorld(WorldConfig(door=door))
    handle_y = float(probe.door_ground_truth().handle_grasp_pose[1, 3])
    probe.close()
    lateral = handle_y + hinge.sign * handle_offset
    return DoorWorld(WorldConfig(door=door, stance=StanceConfig(distance=reach, lateral_offset=lateral)))


def motion_setup(world: DoorWorld, kinematics: RobotKinematics, estimate: DoorEstimate,
                 side: Side | None = None, door_angles: tuple[float, float] = (0.0, 0.0)) -> MotionSetup:
    """The motion-library set-up from the world's measured posture and a door estimate taken
    before the door moved (as the detector's is)."""
    push = world.config.door.opening is DoorOpening.PUSH
    hand = Side(estimate.hinge_side.grasp_hand("push" if push else "pull")) if side is None else side
    body_q = kinematics.configuration({k: v for k, v in world.joint_positions().items()
                                       if k in kinematics.joint_names})
    chain = ArmChain(kinematics, hand, body_q)
    door = door_model_from_estimate(estimate, np.linalg.inv(world.base_pose()), push=push)
    return MotionSetup(chain, door, estimate.width, support_polygon(chain), door_angles)


def talos_kinematics() -> RobotKinematics:
    return RobotKinematics(load_profile("talos"))
