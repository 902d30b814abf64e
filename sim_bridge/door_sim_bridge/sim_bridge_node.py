"""ROS 2 node ``/sim_bridge``: the PyBullet world standing in for the robot's hardware.

Steps the :class:`~door_sim_bridge.world.DoorWorld` from a timer (as fast as possible, or paced to the
wall clock), publishes /clock, joint states, odometry, the head camera and the door's ground truth at
their rates (simulated time), executes joint trajectories and footstep plans one at a time, and serves
the hands' grasp services (every call answered). Every execution ends with an ExecutionOutcome on
/sim/execution_outcome whose request id is the stamp (ns) of the executed message; bad input is
rejected there with its reason and moves nothing. Stopping (ros2_control's convention): a
JointTrajectory without points holds the arm where it is, an empty footstep Path ends the walk at the
next stable stance; the dead-man (:mod:`door_sim_bridge.deadman`) does the same when the supervisor
falls silent; each reports STOPPED with the reason. The loop (executions, steps, the publications
due, a bug in a tick contained) is :mod:`door_sim_bridge.simulation_loop`.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from functools import partial
from typing import Any

from diagnostic_msgs.msg import DiagnosticArray
from nav_msgs.msg import Path
from rclpy.node import Node
from std_msgs.msg import Float64, String
from std_srvs.srv import SetBool
from trajectory_msgs.msg import JointTrajectory

from door_contract.converters.diagnostics import Health
from door_contract.converters.footsteps import path_to_footsteps
from door_contract.converters.stop import is_stop
from door_contract.converters.trajectory import msg_to_joint_path
from door_contract.errors import ContractError
from door_contract.node_support import (
    Heartbeat,
    as_parameter_error,
    create_contract_publisher,
    create_contract_subscription,
    declare_parameters,
    node_main,
)
from door_contract.payloads import ExecutionKind, ExecutionOutcome, OutcomeStatus, encode
from door_contract.stamps import stamp_ns
from door_contract.topics import Services, Topics
from door_contract.vocabulary import Side
from door_robot.crouch import crouch_problem, walking_height
from door_robot.errors import RobotModelError
from door_robot.meshes import MeshUris
from door_sim_bridge.deadman import DeadMan
from door_sim_bridge.errors import SimulationError
from door_sim_bridge.execution import Execution, FootstepExecution, TrajectoryExecution
from door_sim_bridge.parameters import BRIDGE_PARAMETERS, NODE_NAME
from door_sim_bridge.sensor_publication import SensorPublication
from door_sim_bridge.simulation_loop import STEPS_PER_TICK, LoopReport, PublicationRates, SimulationLoop, Stream
from door_sim_bridge.world import DoorWorld
from door_sim_bridge.world_parameters import world_config

__all__ = ["SimBridgeNode", "main"]


class SimBridgeNode(Node):
    def __init__(self) -> None:
        super().__init__(NODE_NAME)
        p = declare_parameters(self, BRIDGE_PARAMETERS)
        with as_parameter_error("simulation", SimulationError, RobotModelError):
            self.world = DoorWorld(world_config(p))
        rates = PublicationRates(p["clock_rate"], p["state_rate"], p["tf_rate"], p["camera_rate"],
                                 p["camera_rate_standing"])
        self.loop = SimulationLoop(self.world, DeadMan(p["supervisor_timeout"], p["supervisor_node"]), rates,
                                   p["real_time"], time.monotonic())
        self.heartbeat = Heartbeat(self)
        self.outcome_pub = create_contract_publisher(self, Topics.EXECUTION_OUTCOME)
        self.crouch = 0.0  # m: the walks' crouch, as /walking/crouch set it last
        create_contract_subscription(self, Topics.WALK_CROUCH, self._on_crouch)  # before the plans: taken first
        create_contract_subscription(self, Topics.ARM_TRAJECTORY, self._on_trajectory)
        create_contract_subscription(self, Topics.FOOTSTEP_PLAN, self._on_footsteps)
        create_contract_subscription(self, Topics.DIAGNOSTICS, self._on_diagnostics)
        for side, spec in ((Side.LEFT, Services.LEFT_GRASP), (Side.RIGHT, Services.RIGHT_GRASP)):
            self.create_service(SetBool, spec.name, partial(self._on_grasp, side), qos_profile=spec.qos.to_profile())
        self.publication = SensorPublication(self, self.world, MeshUris(p["mesh_uris"]))
        self.create_timer(0.0 if not p["real_time"] else 1.0 / p["physics_rate"] * STEPS_PER_TICK, self._tick)
        self.get_logger().info(f"ready: {p['robot_profile']}, {p['door_opening']} door hinged {p['hinge_side']}, "
                               f"{p['physics_rate']:.0f} Hz physics, {'real time' if p['real_time'] else 'as fast as possible'}")

    # ------------------------------------------------------------------ commands
    def _on_trajectory(self, msg: JointTrajectory) -> None:
        self._on_command(ExecutionKind.TRAJECTORY, msg, "a JointTrajectory without points (stop and hold)",
                         msg_to_joint_path, TrajectoryExecution.from_joint_path)

    def _on_footsteps(self, msg: Path) -> None:
        crouch = self.crouch
        self._on_command(ExecutionKind.FOOTSTEPS, msg, "an empty footstep plan (stop at the next stable stance)",
                         path_to_footsteps, lambda world, steps: FootstepExecution(world, steps, crouch))

    def _on_crouch(self, msg: Float64) -> None:
        """The crouch of the walks to come (negative: a rise); one outside [−MAX_RISE, MAX_CROUCH] m
        is refused (the last one stays) with a REJECTED footstep outcome (request id 0: it names no plan)."""
        problem = crouch_problem(msg.data)
        if problem:
            self._report(ExecutionOutcome(ExecutionKind.FOOTSTEPS, 0, OutcomeStatus.REJECTED,
                                          f"/walking/crouch refused: {problem}; walks keep {self.crouch:.3f} m"))
            return
        if msg.data != self.crouch:
            self.get_logger().info(f"walks from now on {walking_height(msg.data)}")
        self.crouch = float(msg.data)

    def _on_command(self, kind: ExecutionKind, msg: Any, stop_reason: str,
                    convert: Callable[[Any], Any], build: Callable[[DoorWorld, Any], Execution]) -> None:
        """An empty command stops the running execution of its kind; else the message is
        converted (a ContractError rejects it, naming why) and handed to the loop."""
        if is_stop(msg):
            self._handle(self.loop.stop(kind, stop_reason))
            return
        request_id = stamp_ns(msg.header.stamp)
        try:
            command = convert(msg)
        except ContractError as error:
            self._report(ExecutionOutcome(kind, request_id, OutcomeStatus.REJECTED, str(error)))
            return
        self._handle(self.loop.submit(kind, request_id, lambda world: build(world, command)))

    def _on_diagnostics(self, msg: DiagnosticArray) -> None:
        if any(status.name == self.loop.deadman.supervisor for status in msg.status):
            if self.loop.supervisor_beat(time.monotonic()):
                self.get_logger().info(f"supervisor /{self.loop.deadman.supervisor} is back: executions accepted")

    def _on_grasp(self, side: Side, request: SetBool.Request, response: SetBool.Response) -> SetBool.Response:
        success, message, report = self.loop.grasp(side, bool(request.data))
        self._handle(report)
        response.success, response.message = success, message
        self.get_logger().info(f"{side.value} hand {'close' if request.data else 'open'}: {message}")
        return response

    def _handle(self, report: LoopReport) -> None:
        """Log and publish what the loop reports (rclpy: one severity per call site)."""
        for line in report.errors:
            self.get_logger().error(line)
        for line in report.warnings:
            self.get_logger().warning(line)
        for line in report.notes:
            self.get_logger().info(line)
        for outcome in report.outcomes:
            self._report(outcome)

    def _report(self, outcome: ExecutionOutcome) -> None:
        self.outcome_pub.publish(String(data=encode(outcome)))
        if outcome.status is OutcomeStatus.SUCCESS:
            self.get_logger().info(f"{outcome.kind.value} {outcome.request_id}: success in {outcome.duration_s:.2f} s")
        else:
            self.get_logger().warning(f"{outcome.kind.value} {outcome.request_id}: {outcome.status.value}: "
                                      f"{outcome.reason}")

    # ------------------------------------------------------------------ the loop
    def _tick(self) -> None:
        self._handle(self.loop.tick(time.monotonic(), self._publish))

    def _publish(self, now: float, streams: tuple[Stream, ...]) -> None:
        self.publication.publish(now, streams)
        if Stream.STATE in streams:  # a contained bug is an ERROR on /diagnostics (tick_faults counts them)
            self.heartbeat.update(Health.ERROR if self.loop.fault_count else Health.OK, "running",
                                  **self.loop.status(time.monotonic()), crouch=f"{self.crouch:.3f}")

    def destroy_node(self) -> None:
        self.world.close()
        super().destroy_node()


main = node_main(SimBridgeNode, __name__)
