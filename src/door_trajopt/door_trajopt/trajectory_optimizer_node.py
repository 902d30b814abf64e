"""ROS 2 node ``/trajectory_optimizer``: door motions as optimised joint trajectories.

A :class:`~door_contract.payloads.MotionRequest` names the motion; the node takes the last
door estimate, joint states and odometry, plans with the motion library (SQP or
constrained CHOMP), publishes the time-parameterised trajectory on
``/trajectory_optimizer/trajectory`` and then a PlanningOutcome (cost, max violation,
iterations, time, the trajectory's stamp, the door angle it ends at). Missing, stale or
non-finite inputs and infeasible plans give a failure outcome naming the reason. Every
request whose id can be read gets exactly one outcome; planning runs on a worker thread
(the robot model is used there only), the newest request or a cancel on
``/trajectory_optimizer/cancel`` supersedes an older one (:mod:`door_contract.planner_service`).
The library job of a request and its outcome are built by :mod:`door_trajopt.requests`.
"""

from __future__ import annotations

from collections.abc import Callable

from rclpy.node import Node
from sensor_msgs.msg import JointState
from std_msgs.msg import String

from door_contract.converters.diagnostics import Health
from door_contract.converters.joint_state import joint_state_to_positions
from door_contract.converters.trajectory import joint_path_to_msg
from door_contract.errors import ContractError
from door_contract.node_support import (
    Heartbeat,
    as_parameter_error,
    create_contract_publisher,
    create_contract_subscription,
    declare_parameters,
    node_main,
)
from door_contract.payloads import DoorEstimate, MotionRequest, OutcomeStatus, encode
from door_contract.planner_desk import PlannerDesk
from door_contract.planner_inputs import PlannerInputs
from door_contract.planner_service import Finished
from door_contract.stamps import UniqueStamps, stamp_ns, time_msg_of_ns
from door_contract.topics import Topics
from door_contract.vocabulary import Backend
from door_robot.errors import RobotModelError
from door_robot.kinematics import RobotKinematics
from door_robot.profile import load_profile
from door_trajopt.library import MotionLibrary, MotionPlan
from door_trajopt.motions import DoorStateOutOfRange, MotionOptions
from door_trajopt.parameters import NODE_NAME, OPTIMIZER_PARAMETERS
from door_trajopt.problem import TrajoptError
from door_trajopt.requests import PlanningRefused, Snapshot, motion_job, planning_outcome

__all__ = ["TrajectoryOptimizerNode", "main"]

BAD_INPUT = (PlanningRefused, RobotModelError, ContractError, DoorStateOutOfRange)
"""What a request's planning raises for bad input (answered REJECTED); anything else (any other
:class:`~door_trajopt.problem.TrajoptError`, of a built problem, included) is a bug (FAILURE)."""


class TrajectoryOptimizerNode(Node):
    def __init__(self) -> None:
        super().__init__(NODE_NAME)
        p = declare_parameters(self, OPTIMIZER_PARAMETERS)
        self.parameters = p
        with as_parameter_error(f"parameter 'robot_profile' = {p['robot_profile']!r}", RobotModelError):
            self.kinematics = RobotKinematics(load_profile(p["robot_profile"]))
        with as_parameter_error("motion library options", TrajoptError):
            self.library = MotionLibrary(MotionOptions(
                waypoints=p["waypoints"], handle_turn=p["handle_turn"], push_angle=p["push_angle"],
                pull_angle=p["pull_angle"]), starts=p["initial_guesses"], velocity_scale=p["velocity_scale"])
        self.lever_radius = p["lever_radius"]
        self.joint_positions: dict[str, float] | None = None
        self.heartbeat = Heartbeat(self)
        self.inputs = PlannerInputs(self, self.heartbeat)
        self.trajectory_pub = create_contract_publisher(self, Topics.MOTION_PROPOSAL)
        self.outcome_pub = create_contract_publisher(self, Topics.MOTION_OUTCOME)
        create_contract_subscription(self, Topics.JOINT_STATES, self._on_joint_states)
        self.stamps = UniqueStamps()
        self.desk = PlannerDesk(self, self.heartbeat, MotionRequest, (Topics.MOTION_REQUEST, Topics.MOTION_CANCEL),
                                lambda r: self.inputs.doors.pick(r.door_stamp, r.door), self._job_for,
                                self._deliver_one, lambda rid, why: self._answer(rid, "?", None, OutcomeStatus.REJECTED, why))
        self.get_logger().info(f"ready: {p['robot_profile']}, default backend {p['backend']}")

    def _on_joint_states(self, msg: JointState) -> None:
        try:
            self.joint_positions = joint_state_to_positions(msg)
        except ContractError as error:
            self.joint_positions = None
            self.get_logger().warning(f"joint states rejected: {error}")

    def _job_for(self, request: MotionRequest, estimate: DoorEstimate | None) -> Callable[[], MotionPlan]:
        """The planning job of ``request`` over the inputs as they are now (the measured state)."""
        base = None if self.inputs.base_pose is None else self.inputs.base_pose.copy()
        snapshot = Snapshot(None if self.joint_positions is None else dict(self.joint_positions), base, estimate)
        return lambda: self._plan(request, snapshot)

    def _deliver_one(self, finished: Finished) -> None:
        """On the executor thread: one outcome per finished request, and the trajectory if proposed."""
        request, plan = finished.request, finished.result
        def answer(status: OutcomeStatus, reason: str, plan: MotionPlan | None = None, stamp: int = -1) -> None:
            self._answer(request.request_id, request.motion, request.backend, status, reason, plan, stamp)
        settled = finished.answer_without_result(BAD_INPUT)
        if settled is not None:
            if settled[0] is OutcomeStatus.FAILURE:  # a bug: a failure outcome, not a dead node
                self.get_logger().error(f"request {request.request_id} crashed the optimiser: {finished.error!r}")
            return answer(*settled)
        if not plan.succeeded:
            result = plan.result
            return answer(OutcomeStatus.FAILURE, f"{result.outcome.value}: constraint '{result.violated_constraint}' "
                          f"violated by {result.max_violation:.3g} after {plan.attempts} initial guesses", plan)
        trajectory = joint_path_to_msg(plan.path)
        trajectory.header.stamp = time_msg_of_ns(self.stamps.next(self.get_clock().now().nanoseconds))
        self.trajectory_pub.publish(trajectory)
        answer(OutcomeStatus.SUCCESS, "", plan, stamp_ns(trajectory.header.stamp))

    def _plan(self, request: MotionRequest, snapshot: Snapshot) -> MotionPlan:
        """On the worker thread (the only user of the robot model and the library)."""
        job = motion_job(request, snapshot, self.kinematics, self.library.options, Backend(self.parameters["backend"]),
                         self.lever_radius)
        self.get_logger().info(f"planning {job.motion.value} with the {job.side.value} arm ({job.backend.value})")
        return self.library.plan(job.motion, job.setup, job.start, job.backend, variant=request.request_id,
                                 attempt=request.attempt)

    def _answer(self, request_id: int, motion: str, backend: Backend | None, status: OutcomeStatus, reason: str,
                plan: MotionPlan | None = None, proposal_stamp_ns: int = -1) -> None:
        outcome = planning_outcome(request_id, status, reason, plan, Backend(backend or self.parameters["backend"]),
                                   proposal_stamp_ns)
        self.outcome_pub.publish(String(data=encode(outcome)))
        line = f"request {request_id} ({motion}): {status.value}"
        if status is OutcomeStatus.SUCCESS and plan is not None:  # rclpy: one severity per call site
            self.get_logger().info(f"{line} in {plan.planning_time_s * 1000:.0f} ms ({plan.result.iterations} "
                                   f"iterations, guess {plan.attempts}; {plan.result.message or 'converged'})")
        else:
            self.get_logger().warning(f"{line}: {reason}")
        self.heartbeat.update(Health.OK if status is OutcomeStatus.SUCCESS else Health.WARN,
                              f"last: {motion} {status.value}",
                              last_planning_ms=round(plan.planning_time_s * 1000.0, 1) if plan else "-")

    def destroy_node(self) -> None:
        self.desk.close()
        super().destroy_node()


main = node_main(TrajectoryOptimizerNode, __name__)
