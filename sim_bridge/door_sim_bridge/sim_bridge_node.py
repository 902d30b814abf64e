"""ROS 2 node ``/sim_bridge``: the PyBullet world standing in for the robot's hardware.

Steps the :class:`~door_sim_bridge.world.DoorWorld` from a timer (as fast as possible, or
paced to the wall clock), publishes /clock, joint states, odometry, the head camera and the
door's ground truth at their rates (simulated time), executes joint trajectories and
footstep plans one at a time, and serves the hands' grasp services (every call answered).
Every execution ends with an ExecutionOutcome on /sim/execution_outcome whose request id is
the stamp (ns) of the executed message; bad input is rejected there with its reason and
moves nothing. Stopping (ros2_control's convention): a JointTrajectory without points holds
the arm where it is, an empty footstep Path ends the walk at the next stable stance; the
dead-man (:mod:`door_sim_bridge.deadman`) does the same when the supervisor falls silent.
Each stopped execution reports STOPPED with the reason.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

import numpy as np
from nav_msgs.msg import Odometry, Path
from rclpy.node import Node
from rosgraph_msgs.msg import Clock
from std_msgs.msg import String
from std_srvs.srv import SetBool
from trajectory_msgs.msg import JointTrajectory

from door_contract.converters.camera_info import intrinsics_to_camera_info
from door_contract.converters.footsteps import footsteps_to_path, path_to_footsteps
from door_contract.converters.image import array_to_image
from door_contract.converters.joint_state import positions_to_joint_state
from door_contract.converters.pose import matrix_to_pose, matrix_to_pose_stamped
from door_contract.converters.trajectory import msg_to_joint_path
from door_contract.errors import ContractError
from door_contract.frames import Frame
from door_contract.node_support import (
    Heartbeat,
    as_parameter_error,
    create_contract_publisher,
    create_contract_subscription,
    declare_parameters,
    node_main,
)
from door_contract.payloads import ExecutionKind, ExecutionOutcome, OutcomeStatus, encode
from door_contract.stamps import stamp_ns, to_time_msg
from door_contract.topics import Services, Topics
from door_contract.vocabulary import Foot, Side
from door_robot.errors import RobotModelError
from door_robot.meshes import MeshUris
from door_sim_bridge.deadman import DeadMan
from door_sim_bridge.errors import SimulationError
from door_sim_bridge.execution import FootstepExecution, TrajectoryExecution
from door_sim_bridge.parameters import BRIDGE_PARAMETERS, NODE_NAME
from door_sim_bridge.robot_state_publication import RobotStatePublication
from door_sim_bridge.schedule import Schedule
from door_sim_bridge.world import DoorWorld
from door_sim_bridge.world.door import HANDLE_JOINT, HINGE_JOINT
from door_sim_bridge.world_parameters import world_config

STEPS_PER_TICK = 4


class SimBridgeNode(Node):
    def __init__(self) -> None:
        super().__init__(NODE_NAME)
        p = declare_parameters(self, BRIDGE_PARAMETERS)
        self.parameters = p
        with as_parameter_error("simulation", SimulationError, RobotModelError):
            self.world = DoorWorld(world_config(p))
        self.deadman = DeadMan(p["supervisor_timeout"], p["supervisor_node"])
        self.schedules = {"clock": Schedule(p["clock_rate"]), "state": Schedule(p["state_rate"]),
                          "camera": Schedule(p["camera_rate"]), "tf": Schedule(p["tf_rate"])}
        self.execution: tuple[TrajectoryExecution | FootstepExecution, ExecutionKind, int] | None = None
        self.previous_base: tuple[float, np.ndarray] | None = None
        self.wall_start = time.monotonic()
        self.heartbeat = Heartbeat(self)
        self._make_interfaces()
        self.robot_state = RobotStatePublication(self, self.world, MeshUris(p["mesh_uris"]), self.world.time)
        self.create_timer(0.0 if not p["real_time"] else 1.0 / p["physics_rate"] * STEPS_PER_TICK, self._tick)
        self.get_logger().info(f"ready: {p['robot_profile']}, {p['door_opening']} door hinged {p['hinge_side']}, "
                               f"{p['physics_rate']:.0f} Hz physics, {'real time' if p['real_time'] else 'as fast as possible'}")

    def _make_interfaces(self) -> None:
        def pub(topic):
            return create_contract_publisher(self, topic)
        self.publishers_by_name = {t: pub(getattr(Topics, t)) for t in (
            "CLOCK", "JOINT_STATES", "ODOM", "COLOR_IMAGE", "COLOR_INFO", "DEPTH_IMAGE", "DEPTH_INFO",
            "CAMERA_POSE", "DOOR_JOINT_STATES", "EXECUTION_OUTCOME", "FOOT_POSES")}
        create_contract_subscription(self, Topics.ARM_TRAJECTORY, self._on_trajectory)
        create_contract_subscription(self, Topics.FOOTSTEP_PLAN, self._on_footsteps)
        create_contract_subscription(self, Topics.DIAGNOSTICS, self._on_diagnostics)
        for side, spec in ((Side.LEFT, Services.LEFT_GRASP), (Side.RIGHT, Services.RIGHT_GRASP)):
            self.create_service(SetBool, spec.name, lambda request, response, s=side: self._on_grasp(s, request, response),
                                qos_profile=spec.qos.to_profile())

    # ------------------------------------------------------------------ commands
    def _on_trajectory(self, msg: JointTrajectory) -> None:
        self._on_command(ExecutionKind.TRAJECTORY, msg, not msg.points,
                         "a JointTrajectory without points (stop and hold)", msg_to_joint_path,
                         lambda path: TrajectoryExecution.from_joint_path(self.world, path))

    def _on_footsteps(self, msg: Path) -> None:
        self._on_command(ExecutionKind.FOOTSTEPS, msg, not msg.poses,
                         "an empty footstep plan (stop at the next stable stance)", path_to_footsteps,
                         lambda steps: FootstepExecution(self.world, steps))

    def _on_command(self, kind: ExecutionKind, msg: Any, empty: bool, stop_reason: str,
                    convert: Callable[[Any], Any], build: Callable[[Any], Any]) -> None:
        """An empty command stops the running execution of its kind; else the message is
        converted (a ContractError rejects it, naming why) and its execution built and started
        (any error there is a bug: a failure outcome, not a dead node)."""
        if empty:
            self._stop(kind, stop_reason)
            return
        request_id = stamp_ns(msg.header.stamp)
        try:
            command = convert(msg)
        except ContractError as error:
            self._report(ExecutionOutcome(kind, request_id, OutcomeStatus.REJECTED, str(error)))
            return
        try:
            execution = build(command)
        except Exception as error:  # a bug must end in a failure outcome, not a dead node
            self._internal_error(kind, request_id, error)
            return
        self._start(execution, kind, request_id)

    def _stop(self, kind: ExecutionKind | None, why: str) -> None:
        """Stop the running execution if it is of ``kind`` (None: any); it reports STOPPED."""
        if self.execution is None or kind not in (None, self.execution[1]):
            self.get_logger().info(f"stop ({why}): no {kind.value if kind else ''} execution running")
            return
        self.get_logger().warning(f"stopping {self.execution[1].value} {self.execution[2]}: {why}")
        self.execution[0].stop(why)

    def _on_diagnostics(self, msg) -> None:
        if any(status.name == self.deadman.supervisor for status in msg.status):
            if self.deadman.beat(time.monotonic()):
                self.get_logger().info(f"supervisor /{self.deadman.supervisor} is back: executions accepted")

    def _start(self, execution, kind: ExecutionKind, request_id: int) -> None:
        refusal = self.deadman.refusal()
        if refusal is not None:
            self._report(ExecutionOutcome(kind, request_id, OutcomeStatus.REJECTED, refusal))
            return
        if self.execution is not None:
            busy = f"busy executing {self.execution[1].value} {self.execution[2]}"
            self._report(ExecutionOutcome(kind, request_id, OutcomeStatus.REJECTED, busy))
            return
        if execution.done:  # rejected while validating: nothing moved
            self._report(execution.result.outcome(kind, request_id))
            return
        self.get_logger().info(f"executing {kind.value} {request_id}")
        self.execution = (execution, kind, request_id)

    def _on_grasp(self, side: Side, request: SetBool.Request, response: SetBool.Response) -> SetBool.Response:
        result = self.world.grasp(side, bool(request.data))
        response.success, response.message = bool(result.success), result.message
        self.get_logger().info(f"{side.value} hand {'close' if request.data else 'open'}: {result.message}")
        return response

    def _internal_error(self, kind: ExecutionKind, request_id: int, error: Exception) -> None:
        self.get_logger().error(f"{kind.value} {request_id} crashed the execution: {error!r}")
        self._report(ExecutionOutcome(kind, request_id, OutcomeStatus.FAILURE, f"internal error: {error!r}"))

    def _report(self, outcome: ExecutionOutcome) -> None:
        self.publishers_by_name["EXECUTION_OUTCOME"].publish(String(data=encode(outcome)))
        if outcome.status is OutcomeStatus.SUCCESS:
            self.get_logger().info(f"{outcome.kind.value} {outcome.request_id}: success in {outcome.duration_s:.2f} s")
        else:
            self.get_logger().warning(f"{outcome.kind.value} {outcome.request_id}: {outcome.status.value}: "
                                      f"{outcome.reason}")

    # ------------------------------------------------------------------ the loop
    def _tick(self) -> None:
        silence = self.deadman.check(time.monotonic())
        if silence is not None:
            self.get_logger().error(silence)
            self._stop(None, silence)
        if self.parameters["real_time"] and self.world.time > time.monotonic() - self.wall_start:
            return
        for _ in range(STEPS_PER_TICK):
            if self.execution is not None and self.execution[0].command():
                execution, kind, request_id = self.execution
                self.execution = None
                self._report(execution.result.outcome(kind, request_id))
            self.world.step()
            self._publish_due()

    def _publish_due(self) -> None:
        now = self.world.time
        if self.schedules["clock"].due(now):
            self.publishers_by_name["CLOCK"].publish(Clock(clock=to_time_msg(now)))
        if self.schedules["state"].due(now):
            self._publish_state(now)
        if self.parameters["tf_rate"] > 0 and self.schedules["tf"].due(now):
            self.robot_state.publish(now)
        if self.parameters["camera_rate"] > 0 and self.schedules["camera"].due(now):
            self._publish_camera()

    def _publish_state(self, now: float) -> None:
        states = self.world.joint_states()
        msg = positions_to_joint_state(dict(zip(states.names, states.positions)), stamp=now,
                                       velocities=dict(zip(states.names, states.velocities)))
        self.publishers_by_name["JOINT_STATES"].publish(msg)
        base = self.world.base_pose()
        odom = Odometry()
        odom.header.stamp, odom.header.frame_id = to_time_msg(now), Frame.ODOM.value
        odom.child_frame_id = Frame.BASE_LINK.value
        odom.pose.pose = matrix_to_pose(base)
        if self.previous_base is not None and now > self.previous_base[0]:
            velocity = (base[:3, 3] - self.previous_base[1][:3, 3]) / (now - self.previous_base[0])
            odom.twist.twist.linear.x, odom.twist.twist.linear.y, odom.twist.twist.linear.z = (float(v) for v in velocity)
        self.previous_base = (now, base)
        self.publishers_by_name["ODOM"].publish(odom)
        feet = self.world.foot_placements()
        self.publishers_by_name["FOOT_POSES"].publish(footsteps_to_path([feet[Foot.LEFT], feet[Foot.RIGHT]], now))
        door = self.world.door_state()
        self.publishers_by_name["DOOR_JOINT_STATES"].publish(positions_to_joint_state(
            {HINGE_JOINT: door.hinge_angle, HANDLE_JOINT: door.handle_angle}, stamp=now,
            velocities={HINGE_JOINT: door.hinge_velocity, HANDLE_JOINT: door.handle_velocity}))
        self.heartbeat.update(self.heartbeat.health, "running", sim_time=round(now, 2),
                              real_time_factor=round(now / max(time.monotonic() - self.wall_start, 1e-6), 2),
                              executing=self.execution[1].value if self.execution else "-")

    def _publish_camera(self) -> None:
        frame = self.world.render()
        frame_id = Frame.HEAD_CAMERA_OPTICAL.value
        info = intrinsics_to_camera_info(frame.intrinsics, frame_id, frame.time)
        depth = np.where(np.isfinite(frame.depth), frame.depth, np.nan).astype(np.float32)
        self.publishers_by_name["CAMERA_POSE"].publish(matrix_to_pose_stamped(frame.camera_pose, Frame.ODOM.value, frame.time))
        self.publishers_by_name["COLOR_IMAGE"].publish(array_to_image(np.ascontiguousarray(frame.rgb), "rgb8", frame_id, frame.time))
        self.publishers_by_name["COLOR_INFO"].publish(info)
        self.publishers_by_name["DEPTH_IMAGE"].publish(array_to_image(depth, "32FC1", frame_id, frame.time))
        self.publishers_by_name["DEPTH_INFO"].publish(info)

    def destroy_node(self) -> None:
        self.world.close()
        super().destroy_node()


main = node_main(SimBridgeNode, __name__)
