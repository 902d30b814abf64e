"""The simulated door world (ROS-free): configuration, door, robot, camera, grasps.

World frame = ``odom``: the wall's robot-side face is the plane x = 0 with the doorway centred
at y = 0, the floor is z = 0, the robot starts at x = -stance.distance facing +x, and push
doors open towards +x (details in :mod:`door_sim_bridge.world.door`). Start with
:class:`DoorWorld`.
"""

from door_sim_bridge.world.camera import CameraFrame
from door_sim_bridge.world.config import (
                                          CameraConfig,
                                          ContactSolver,
                                          DoorConfig,
                                          ExecutionConfig,
                                          GraspModel,
                                          RobotMode,
                                          RobotVisuals,
                                          StanceConfig,
                                          WindConfig,
                                          WorldConfig,
)
from door_sim_bridge.world.door import HANDLE_JOINT, HINGE_JOINT, DoorGroundTruth, DoorPart, DoorState
from door_sim_bridge.world.grasp import GraspResult
from door_sim_bridge.world.hardware import SoleContact
from door_sim_bridge.world.robot import JointLimit, JointStates
from door_sim_bridge.world.world import DoorWorld, EventKind, SimEvent

__all__ = ["HANDLE_JOINT", "HINGE_JOINT", "CameraConfig", "CameraFrame", "ContactSolver", "DoorConfig",
           "DoorGroundTruth", "DoorPart", "DoorState", "DoorWorld", "EventKind", "ExecutionConfig", "GraspModel",
           "GraspResult", "JointLimit", "JointStates", "RobotMode", "RobotVisuals", "SimEvent", "SoleContact",
           "StanceConfig", "WindConfig", "WorldConfig"]
