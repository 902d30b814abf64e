"""ROS 2 node ``/fsm_supervisor``: runs the door task's state machine (seed 001 Fig. 3).

The node turns topics into machine events and machine actions into publications and
service calls; everything that decides lives in :mod:`door_fsm.machine`. Proposals
(footstep plans, trajectories) are matched to their planning outcome through the stamp
the planner gives them (``details['stamp_ns']``); executions are matched through the
stamp this node gives what it sends.
"""

from __future__ import annotations

import time

from nav_msgs.msg import Path
from rclpy.node import Node
from std_msgs.msg import String
from std_srvs.srv import SetBool
from trajectory_msgs.msg import JointTrajectory

from door_contract.converters.diagnostics import Health
from door_contract.errors import ContractError
from door_contract.node_support import (Heartbeat, create_contract_publisher, create_contract_subscription,
                                        declare_parameters, run_node)
from door_contract.payloads import (DoorEstimate, ExecutionOutcome, FootstepRequest, MotionRequest,
                                    OutcomeStatus, PlanningOutcome, TaskReport, decode, encode)
from door_contract.stamps import stamp_ns
from door_contract.topics import Services, Topics
from door_fsm import actions as act
from door_fsm import events as ev
from door_fsm.machine import DoorTaskMachine, MachineOptions
from door_fsm.operator_commands import AutonomyLevel, UnknownCommandError, parse_command
from door_fsm.parameters import NODE_NAME, SUPERVISOR_PARAMETERS
from door_fsm.states import DoorOpening
from door_fsm.summaries import door_summary, plan_summary


class FsmSupervisorNode(Node):
    def __init__(self) -> None:
        super().__init__(NODE_NAME)
        p = declare_parameters(self, SUPERVISOR_PARAMETERS)
        self.parameters = p
        self.machine = DoorTaskMachine(MachineOptions(
            opening=DoorOpening(p["opening"]), autonomy=AutonomyLevel(p["autonomy"]),
            state_timeout_s=p["state_timeout"], approval_timeout_s=p["approval_timeout"],
            max_repeats=p["max_repeats"]))
        self.heartbeat = Heartbeat(self)
        self.door: DoorEstimate | None = None
        self.approved_door: DoorEstimate | None = None  # the estimate DETECT_DOOR proposed
        self.door_angle = 0.0  # rad, as left by the last executed door motion
        self._planned_door_angle = 0.0  # rad, at the end of the motion being executed
        self._detection_request: int | None = None
        self._proposals: dict[int, Path | JointTrajectory] = {}  # planner stamp → message
        self._pending: dict[int, PlanningOutcome] = {}  # outcome waiting for its message
        self._approved: dict[int, Path | JointTrajectory] = {}  # request id → message to send
        self._executing: dict[int, int] = {}  # sent stamp → request id
        self._seen_nodes: set[str] = set()
        self._started = False
        self._make_interfaces()
        self._start_at = time.monotonic() + p["start_delay"]
        self.create_timer(0.1, self._tick)
        self.get_logger().info(f"ready: {p['opening']} door, autonomy {p['autonomy']}, backend {p['backend']}")

    # ------------------------------------------------------------------ wiring to the bus
    def _make_interfaces(self) -> None:
        pub = lambda topic: create_contract_publisher(self, topic)
        self.state_pub, self.approval_pub = pub(Topics.TASK_STATE), pub(Topics.APPROVAL_REQUEST)
        self.report_pub = pub(Topics.TASK_REPORT)
        self.footsteps_pub, self.trajectory_pub = pub(Topics.FOOTSTEP_PLAN), pub(Topics.ARM_TRAJECTORY)
        self.footstep_request_pub, self.motion_request_pub = pub(Topics.FOOTSTEP_REQUEST), pub(Topics.MOTION_REQUEST)
        sub = lambda topic, callback: create_contract_subscription(self, topic, callback)
        sub(Topics.DOOR_ESTIMATE, self._on_door_estimate)
        sub(Topics.FOOTSTEP_PROPOSAL, self._on_proposal_message)
        sub(Topics.MOTION_PROPOSAL, self._on_proposal_message)
        sub(Topics.FOOTSTEP_OUTCOME, self._on_planning_outcome)
        sub(Topics.MOTION_OUTCOME, self._on_planning_outcome)
        sub(Topics.EXECUTION_OUTCOME, self._on_execution_outcome)
        sub(Topics.OPERATOR, self._on_operator)
        self.grasp_clients = {spec.name.split("/")[1].split("_")[0]: self.create_client(spec.srv_class(), spec.name)
                              for spec in Services.all()}

    def _now(self) -> float:
        return time.monotonic()

    def _feed(self, event: ev.Event) -> None:
        self._perform(self.machine.handle(event, self._now()))

    # ------------------------------------------------------------------ inputs
    def _on_door_estimate(self, msg: String) -> None:
        try:
            estimate = decode(DoorEstimate, msg.data)
        except ContractError as error:
            self.get_logger().warning(f"door estimate rejected: {error}")
            return
        self.door = estimate
        if self._detection_request is not None:
            request, self._detection_request = self._detection_request, None
            self.approved_door = estimate
            self._feed(ev.ProposalReady(request, door_summary(estimate)))

    def _on_proposal_message(self, msg: Path | JointTrajectory) -> None:
        stamp = stamp_ns(msg.header.stamp)
        self._proposals[stamp] = msg
        outcome = self._pending.pop(stamp, None)
        if outcome is not None:
            self._accept_proposal(outcome, msg)

    def _on_planning_outcome(self, msg: String) -> None:
        try:
            outcome = decode(PlanningOutcome, msg.data)
        except ContractError as error:
            self.get_logger().warning(f"planning outcome rejected: {error}")
            return
        if outcome.request_id != self.machine.request_id:
            return  # an answer to an earlier request
        if outcome.status is not OutcomeStatus.SUCCESS:
            self._feed(ev.ProposalFailed(outcome.request_id, outcome.reason))
            return
        if "door_angle" in outcome.details:
            self._planned_door_angle = float(outcome.details["door_angle"])
        stamp = int(outcome.details.get("stamp_ns", -1))
        message = self._proposals.pop(stamp, None)
        if message is None:
            self._pending[stamp] = outcome  # the proposal itself has not arrived yet
        else:
            self._accept_proposal(outcome, message)

    def _accept_proposal(self, outcome: PlanningOutcome, message: Path | JointTrajectory) -> None:
        self._approved[outcome.request_id] = message
        self._feed(ev.ProposalReady(outcome.request_id, plan_summary(outcome)))

    def _on_execution_outcome(self, msg: String) -> None:
        try:
            outcome = decode(ExecutionOutcome, msg.data)
        except ContractError as error:
            self.get_logger().warning(f"execution outcome rejected: {error}")
            return
        request = self._executing.pop(outcome.request_id, None)
        if request is None:
            return
        if outcome.slipped:
            self._feed(ev.HandSlipped(outcome.reason))
            return
        if outcome.status is OutcomeStatus.SUCCESS:
            self.door_angle = self._planned_door_angle
        self._feed(ev.ExecutionFinished(request, outcome.status is OutcomeStatus.SUCCESS, outcome.reason))

    def _on_operator(self, msg: String) -> None:
        try:
            command = parse_command(msg.data)
        except UnknownCommandError as error:
            self.get_logger().warning(str(error))
            return
        self.get_logger().info(f"operator: {command.value}")
        self._feed(ev.OperatorSaid(command))

    def _tick(self) -> None:
        if not self._started:
            self._start_when_ready()
            return
        self._check_nodes()
        self._perform(self.machine.tick(self._now()))

    def _start_when_ready(self) -> None:
        """Start once start_delay has passed and every required node is up (the planning
        time of DETECT_DOOR is then the detector's, not the graph's start-up), or anyway
        after graph_timeout more, naming the absent nodes."""
        now = self._now()
        if now < self._start_at:
            return
        missing = sorted(set(self.parameters["required_nodes"]) - set(self.get_node_names()))
        if missing and now < self._start_at + self.parameters["graph_timeout"]:
            self.heartbeat.update(self.heartbeat.health, f"waiting for {', '.join(missing)}")
            return
        if missing:
            self.get_logger().warning(f"starting without {', '.join(missing)}: not up after "
                                      f"{self.parameters['graph_timeout']:.0f} s")
        self._started = True
        self._perform(self.machine.start(now))

    def _check_nodes(self) -> None:
        present = set(self.get_node_names())
        required = set(self.parameters["required_nodes"])
        if not (present & required) <= self._seen_nodes:
            self._seen_nodes |= present & required
            self.heartbeat.update(self.heartbeat.health, self.heartbeat.message,
                                  watching=",".join(sorted(self._seen_nodes)))
        for name in sorted(self._seen_nodes - present):
            self._seen_nodes.discard(name)
            self._feed(ev.NodeLost(name))

    # ------------------------------------------------------------------ outputs
    def _perform(self, actions: list[act.Action]) -> None:
        for action in actions:
            handler = getattr(self, f"_do_{type(action).__name__}")
            handler(action)

    def _do_AnnounceState(self, action: act.AnnounceState) -> None:
        self.state_pub.publish(String(data=action.state))
        health = Health.ERROR if action.state == "FAILED" else Health.OK
        self.heartbeat.update(health, action.state, reason=action.reason or "-",
                              failure=self.machine.failure_reason or "-")
        self.get_logger().info(f"state {action.state}" + (f" ({action.reason})" if action.reason else ""))
        if self.machine.state.is_terminal:
            report = TaskReport(self.machine.state.value, self.machine.failure_reason,
                                self.parameters["opening"], self.parameters["autonomy"],
                                tuple(self.machine.report()))
            self.report_pub.publish(String(data=encode(report)))

    def _do_AskApproval(self, action: act.AskApproval) -> None:
        self.approval_pub.publish(String(data=action.text))
        self.get_logger().info(f"waiting for the operator: {action.text}")

    def _do_ClearApproval(self, action: act.ClearApproval) -> None:
        self.approval_pub.publish(String(data=""))

    def _do_Notice(self, action: act.Notice) -> None:
        self.get_logger().warning(action.text)

    def _do_RequestDetection(self, action: act.RequestDetection) -> None:
        self._detection_request = action.request_id

    def _do_RequestFootsteps(self, action: act.RequestFootsteps) -> None:
        request = FootstepRequest(action.request_id, action.goal, self.parameters["opening"], self.door_angle,
                                  self._approved_door_stamp(), self._approved_door_json())
        self.footstep_request_pub.publish(String(data=encode(request)))

    def _do_RequestMotion(self, action: act.RequestMotion) -> None:
        request = MotionRequest(action.request_id, action.motion, self.parameters["opening"],
                                self.parameters["backend"], self.door_angle, self._approved_door_stamp(),
                                self._approved_door_json())
        self.motion_request_pub.publish(String(data=encode(request)))

    def _approved_door_stamp(self) -> float:
        """The stamp of the door estimate DETECT_DOOR accepted: later estimates (seen up close,
        while walking) do not silently replace what the operator approved."""
        return self.approved_door.stamp if self.approved_door is not None else -1.0

    def _approved_door_json(self) -> str:
        return encode(self.approved_door) if self.approved_door is not None else ""

    def _do_CallGrasp(self, action: act.CallGrasp) -> None:
        door = self.approved_door or self.door
        hand = door.hinge_side.grasp_hand(self.parameters["opening"]) if door else "right"
        client = self.grasp_clients[hand]
        if not client.service_is_ready():
            self._feed(ev.GraspAnswered(action.request_id, False, f"/{hand}_hand/grasp is not available"))
            return
        future = client.call_async(SetBool.Request(data=action.close))
        future.add_done_callback(lambda f, rid=action.request_id: self._feed(
            ev.GraspAnswered(rid, bool(f.result() and f.result().success),
                             f.result().message if f.result() else "no answer")))

    def _do_Execute(self, action: act.Execute) -> None:
        message = self._approved.pop(action.request_id)
        message.header.stamp = self.get_clock().now().to_msg()
        self._executing[stamp_ns(message.header.stamp)] = action.request_id
        (self.footsteps_pub if isinstance(message, Path) else self.trajectory_pub).publish(message)


def main(args: list[str] | None = None) -> int:
    return run_node(FsmSupervisorNode, args)


if __name__ == "__main__":
    raise SystemExit(main())
