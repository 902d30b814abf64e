"""ROS 2 node ``/fsm_supervisor``: runs the door task's state machine ([Banerjee 2015] Fig. 3).

Thin glue: topics become machine events, machine actions become publications and service
calls. Deciding lives in :mod:`door_fsm.machine`, pairing answers with requests in
:mod:`door_fsm.exchange`, the door's context in :mod:`door_fsm.door_context`. Deadlines:
planning and approval on the steady clock, executions on the node's ROS clock (sim time
under ``use_sim_time``); docs/CLOCKS.md.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from nav_msgs.msg import Path
from rclpy.clock import Clock, ClockType
from rclpy.node import Node
from std_msgs.msg import String
from std_srvs.srv import SetBool
from trajectory_msgs.msg import JointTrajectory

from door_contract.converters.diagnostics import Health
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
from door_contract.payloads import ExecutionOutcome, OutcomeStatus, PlanningCancel, PlanningOutcome, decode, encode
from door_contract.stamps import UniqueStamps, stamp_ns, time_msg_of_ns
from door_contract.topics import Services, Topics, TopicSpec
from door_contract.vocabulary import DoorOpening
from door_fsm import actions as act
from door_fsm import events as ev
from door_fsm.answers import execution_event, planning_event, usable_door_estimate
from door_fsm.door_context import DoorContext
from door_fsm.exchange import PlanExchange, Proposal
from door_fsm.graph_watch import GraphWatch
from door_fsm.machine import DoorTaskMachine, MachineOptions, MachineOptionsError
from door_fsm.operator_commands import AutonomyLevel, UnknownCommandError, parse_command
from door_fsm.parameters import NODE_NAME, SUPERVISOR_PARAMETERS
from door_fsm.records import Instant
from door_fsm.summaries import door_summary, task_report, work_of
from door_robot.errors import RobotModelError
from door_robot.profile import load_profile

HEARTBEAT_PERIOD_S = 0.25
KINDS = {"footsteps": (Topics.FOOTSTEP_PROPOSAL, Topics.FOOTSTEP_OUTCOME, Topics.FOOTSTEP_CANCEL),
         "motion": (Topics.MOTION_PROPOSAL, Topics.MOTION_OUTCOME, Topics.MOTION_CANCEL)}


class FsmSupervisorNode(Node):
    def __init__(self) -> None:
        super().__init__(NODE_NAME)
        p = self.parameters = declare_parameters(self, SUPERVISOR_PARAMETERS)
        with as_parameter_error(f"parameter 'robot_profile' = {p['robot_profile']!r}", RobotModelError):
            step_duration = load_profile(p["robot_profile"]).walking.step_duration
        with as_parameter_error("fsm_supervisor timeouts", MachineOptionsError):
            self.machine = DoorTaskMachine(MachineOptions(
                opening=DoorOpening(p["opening"]), autonomy=AutonomyLevel(p["autonomy"]),
                planning_timeout_s=p["planning_timeout"], approval_timeout_s=p["approval_timeout"],
                execution_factor=p["execution_timeout_factor"], execution_margin_s=p["execution_timeout_margin"],
                max_repeats=p["max_repeats"]))
        self.door = DoorContext(DoorOpening(p["opening"]), p["backend"])
        self.exchange = PlanExchange(lambda message: work_of(message, step_duration))
        # 4 Hz: the sim bridge's dead-man stops the robot when this heartbeat falls silent
        self.heartbeat = Heartbeat(self, period_s=HEARTBEAT_PERIOD_S)
        self.stamps, self.steady = UniqueStamps(), Clock(clock_type=ClockType.STEADY_TIME)
        self.graph = GraphWatch(set(p["required_nodes"]), self._seconds(self.steady) + p["start_delay"],
                                p["graph_timeout"])
        self._detection_request: int | None = None
        self._handlers: dict[type, Callable[[Any], None]] = {act.AnnounceState: self._announce, act.AskApproval: self._ask, act.ClearApproval:
                          lambda a: self.approval_pub.publish(String(data="")),
                          act.Notice: lambda a: self.get_logger().warning(a.text),
                          act.RequestDetection: self._request_detection, act.RequestFootsteps: self._request_footsteps,
                          act.RequestMotion: self._request_motion, act.CancelPlanning: self._cancel,
                          act.StopMotion: self._stop, act.CallGrasp: self._call_grasp, act.Execute: self._execute}
        self._make_interfaces()
        self.create_timer(0.1, self._tick, clock=self.steady)  # runs even when /clock stops
        self.get_logger().info(f"ready: {p['opening']} door, autonomy {p['autonomy']}, backend {p['backend']}")

    def _make_interfaces(self) -> None:
        def pub(topic: TopicSpec) -> Any:
            return create_contract_publisher(self, topic)

        self.state_pub, self.approval_pub, self.report_pub = (pub(t) for t in (
            Topics.TASK_STATE, Topics.APPROVAL_REQUEST, Topics.TASK_REPORT))
        self.footsteps_pub, self.trajectory_pub = pub(Topics.FOOTSTEP_PLAN), pub(Topics.ARM_TRAJECTORY)
        self.request_pubs = {"footsteps": pub(Topics.FOOTSTEP_REQUEST), "motion": pub(Topics.MOTION_REQUEST)}
        self.cancel_pubs = {kind: pub(topics[2]) for kind, topics in KINDS.items()}

        def sub(topic: TopicSpec, callback: Callable[..., None]) -> Any:
            return create_contract_subscription(self, topic, callback)

        for kind, (proposal, outcome, _) in KINDS.items():
            sub(proposal, lambda m, k=kind: self._feed_answer(self.exchange.add_message(k, stamp_ns(m.header.stamp), m)))
            sub(outcome, lambda m, k=kind: self._on_planning_outcome(k, m))
        sub(Topics.DOOR_ESTIMATE, self._on_door_estimate)
        sub(Topics.EXECUTION_OUTCOME, self._on_execution_outcome)
        sub(Topics.OPERATOR, self._on_operator)
        self.grasp_clients = {spec.name.split("/")[1].split("_")[0]: self.create_client(
            spec.srv_class(), spec.name, qos_profile=spec.qos.to_profile()) for spec in Services.all()}

    @staticmethod
    def _seconds(clock: Clock) -> float:
        return clock.now().nanoseconds * 1e-9

    def _now(self) -> Instant:
        return Instant(self._seconds(self.steady), self._seconds(self.get_clock()))

    def _feed(self, event: ev.Event) -> None:
        self._run(self.machine.handle(event, self._now()))

    def _run(self, actions: list[act.Action]) -> None:
        for action in actions:
            self._handlers[type(action)](action)
        self.exchange.begin(self.machine.request_id)  # answers to older requests are stale now

    # ------------------------------------------------------------------ inputs
    def _on_door_estimate(self, msg: String) -> None:
        try:
            estimate = usable_door_estimate(msg.data)
        except ContractError as error:
            self.get_logger().warning(f"door estimate rejected: {error}")
            return
        self.door.latest = estimate
        if self._detection_request is not None:
            request, self._detection_request = self._detection_request, None
            self.door.approved = estimate
            self._feed(ev.ProposalReady(request, door_summary(estimate)))

    def _on_planning_outcome(self, kind: str, msg: String) -> None:
        try:
            self._feed_answer(self.exchange.add_outcome(kind, decode(PlanningOutcome, msg.data)))
        except ContractError as error:
            self.get_logger().warning(f"planning outcome rejected: {error}")

    def _feed_answer(self, answer: Proposal | PlanningOutcome | None) -> None:
        if answer is not None:
            if isinstance(answer, Proposal):
                self.door.planned(answer.outcome)
            self._feed(planning_event(answer))

    def _on_execution_outcome(self, msg: String) -> None:
        try:
            outcome = decode(ExecutionOutcome, msg.data)
        except ContractError as error:
            self.get_logger().warning(f"execution outcome rejected: {error}")
            return
        request = self.exchange.finished(outcome.request_id)
        if request is not None:
            if outcome.status is OutcomeStatus.SUCCESS and not outcome.slipped:
                self.door.executed()
            self._feed(execution_event(outcome, request))

    def _on_operator(self, msg: String) -> None:
        try:
            word = parse_command(msg.data)
        except UnknownCommandError as error:
            self.get_logger().warning(str(error))
            return
        self.get_logger().info(f"operator: {word}")
        self._feed(ev.OperatorSaid(word))

    def _tick(self) -> None:
        now = self._now()
        step = self.graph.step(now.wall, set(self.get_node_names()))
        self.heartbeat.update(self.heartbeat.health, step.message or self.heartbeat.message,
                              watching=",".join(sorted(self.graph.seen)))
        if step.warning:
            self.get_logger().warning(step.warning)
        if step.start:
            self._run(self.machine.start(now))
        for name in step.lost:
            self._feed(ev.NodeLost(name))
        if self.graph.started:
            self._run(self.machine.tick(now))

    # ------------------------------------------------------------------ outputs
    def _announce(self, action: act.AnnounceState) -> None:
        self.state_pub.publish(String(data=action.state))
        health = Health.ERROR if action.state == "FAILED" else Health.OK
        self.heartbeat.update(health, action.state, reason=action.reason or "-", failure=self.machine.failure_reason or "-")
        self.get_logger().info(f"state {action.state}" + (f" ({action.reason})" if action.reason else ""))
        if self.machine.state.is_terminal:
            report = task_report(self.machine.state.value, self.machine.failure_reason, self.door.opening,
                                 self.parameters["autonomy"], self.machine.report(),
                                 "sim" if self.get_parameter("use_sim_time").value else "wall")
            self.report_pub.publish(String(data=encode(report)))

    def _ask(self, action: act.AskApproval) -> None:
        self.approval_pub.publish(String(data=action.text))
        self.get_logger().info(f"waiting for the operator: {action.text}")

    def _request_detection(self, action: act.RequestDetection) -> None:
        self._detection_request = action.request_id

    def _request_footsteps(self, action: act.RequestFootsteps) -> None:
        self.request_pubs["footsteps"].publish(String(data=encode(self.door.footstep_request(action))))

    def _request_motion(self, action: act.RequestMotion) -> None:
        self.request_pubs["motion"].publish(String(data=encode(self.door.motion_request(action))))

    def _cancel(self, action: act.CancelPlanning) -> None:
        self.cancel_pubs[action.kind].publish(String(data=encode(PlanningCancel(action.request_id, action.reason))))

    def _stop(self, action: act.StopMotion) -> None:
        """ros2_control's stop: an empty trajectory holds the arm; an empty path ends the walk."""
        stamp = time_msg_of_ns(self.stamps.next(self.get_clock().now().nanoseconds))
        trajectory, path = JointTrajectory(), Path()
        trajectory.header.stamp, path.header.stamp, path.header.frame_id = stamp, stamp, Frame.ODOM.value
        self.trajectory_pub.publish(trajectory)
        self.footsteps_pub.publish(path)
        self.get_logger().warning(f"stopping all motion: {action.reason}")

    def _call_grasp(self, action: act.CallGrasp) -> None:
        hand = self.door.grasp_hand()
        client = self.grasp_clients[hand]
        if not client.service_is_ready():
            self._feed(ev.GraspAnswered(action.request_id, False, f"/{hand}_hand/grasp is not available"))
            return
        future = client.call_async(SetBool.Request(data=action.close))
        future.add_done_callback(lambda f, rid=action.request_id: self._feed(
            ev.GraspAnswered(rid, bool(f.result() and f.result().success),
                             f.result().message if f.result() else "no answer")))

    def _execute(self, action: act.Execute) -> None:
        proposal = self.exchange.take(action.request_id)
        if proposal is None:
            self._feed(ev.ExecutionFinished(action.request_id, False, "the approved proposal is gone"))
            return
        stamp = self.stamps.next(self.get_clock().now().nanoseconds)
        proposal.message.header.stamp = time_msg_of_ns(stamp)
        self.exchange.sent(stamp, action.request_id)
        (self.footsteps_pub if isinstance(proposal.message, Path) else self.trajectory_pub).publish(proposal.message)


main = node_main(FsmSupervisorNode, __name__)
