"""Shared scenes for motion-library tests: a sim world at the stand pose and its door estimate."""

from __future__ import annotations

import numpy as np

from door_contract.payloads import DoorEstimate
from door_contract.vocabulary import DoorOpening, HingeSide, Side, grasp_hand
from door_robot.kinematics import RobotKinematics
from door_robot.profile import load_profile
from door_sim_bridge.world import DoorConfig, DoorWorld, StanceConfig, WorldConfig
from door_trajopt.chain import ArmChain
from door_trajopt.door_model import door_model_from_estimate
from door_trajopt.motions import MotionSetup, support_polygon
from footstep_planner.footstep_planner_node import door_geometry_from_estimate, planner_options
from footstep_planner.goals import stand_pose_for_opening
from footstep_planner.parameters import PLANNER_PARAMETERS

PLANNER_DEFAULTS = {spec.name: spec.default for spec in PLANNER_PARAMETERS}


def estimate_from_world(world: DoorWorld) -> DoorEstimate:
    """A perfect detector: the estimate the detector should publish, from the ground truth."""
    truth = world.door_ground_truth()
    hinge = world.config.door.hinge_side
    return DoorEstimate(world.time, "odom", tuple(truth.handle_grasp_pose[:3, 3]), tuple(truth.normal), hinge,
                        truth.width, tuple(tuple(c) for c in truth.corners), 1.0, 10, "automatic")


def stand_world(opening: DoorOpening = DoorOpening.PUSH, hinge: HingeSide = HingeSide.LEFT,
                **door_fields: float) -> DoorWorld:
    """The robot where the footstep planner node (default parameters) puts it to open this
    door (``door_fields``: other DoorConfig values): facing it, for pull doors just past the
    latch edge and out of the pulled leaf."""
    door = DoorConfig(opening=opening, hinge_side=hinge, **door_fields)
    probe = DoorWorld(WorldConfig(door=door))
    estimate = estimate_from_world(probe)
    probe.close()
    options = planner_options("talos", {"heuristic_weight": 1.0, "max_expansions": 1000, "max_planning_time": 1.0})
    geometry = door_geometry_from_estimate(estimate, opening, 0.0,
                                           PLANNER_DEFAULTS["handle_standoff"])
    pull = opening is DoorOpening.PULL
    stand = stand_pose_for_opening(geometry, options,
                                   reach=PLANNER_DEFAULTS["stand_reach_pull" if pull else "stand_reach"],
                                   handle_offset=PLANNER_DEFAULTS["stand_handle_offset"],
                                   sweep_half_depth=PLANNER_DEFAULTS["pull_sweep_half_depth"],
                                   pull_sweep_angle=PLANNER_DEFAULTS["pull_sweep_angle"],
                                   beyond_latch=PLANNER_DEFAULTS["pull_stand_beyond_latch"])
    return DoorWorld(WorldConfig(door=door, stance=StanceConfig(distance=-stand.x, lateral_offset=stand.y)))


def motion_setup(world: DoorWorld, kinematics: RobotKinematics, estimate: DoorEstimate,
                 side: Side | None = None, door_angles: tuple[float, float] = (0.0, 0.0)) -> MotionSetup:
    """The motion-library set-up from the world's measured posture and a door estimate taken
    before the door moved (as the detector's is)."""
    push = world.config.door.opening is DoorOpening.PUSH
    hand = grasp_hand(estimate.hinge_side, DoorOpening.PUSH if push else DoorOpening.PULL) if side is None else side
    body_q = kinematics.configuration({k: v for k, v in world.joint_positions().items()
                                       if k in kinematics.joint_names})
    chain = ArmChain(kinematics, hand, body_q)
    door = door_model_from_estimate(estimate, np.linalg.inv(world.base_pose()), push=push)
    return MotionSetup(chain, door, estimate.width, support_polygon(chain), door_angles)


def talos_kinematics() -> RobotKinematics:
    return RobotKinematics(load_profile("talos"))
