"""ROS 2 node ``/fsm_supervisor``: runs the door task's state machine ([Banerjee 2015] Fig. 3).

Thin glue over :class:`door_fsm.supervisor.Supervisor`: topics become its inputs, the actions it
returns become publications and service calls. Deciding lives in :mod:`door_fsm.machine`; the
robot's hands and step time come from ``robot_profile``. Deadlines: planning and approval on the
steady clock, executions on the node's ROS clock (sim time under ``use_sim_time``; docs/CLOCKS.md).
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial
from typing import Any

from rclpy.clock import Clock, ClockType
from rclpy.node import Node
from std_msgs.msg import Float64, String
from std_srvs.srv import SetBool

from door_contract.converters.diagnostics import Health
from door_contract.node_support import (
    Heartbeat,
    as_parameter_error,
    create_contract_publisher,
    create_contract_subscription,
    declare_parameters,
    node_main,
)
from door_contract.payloads import PlanningCancel, encode
from door_contract.topics import PLANNER_TOPICS, Topics, TopicSpec
from door_contract.vocabulary import TaskState
from door_fsm import actions as act
from door_fsm import events as ev
from door_fsm.machine import MachineOptionsError
from door_fsm.parameters import NODE_NAME, SUPERVISOR_PARAMETERS
from door_fsm.records import Instant
from door_fsm.robot_commands import RobotCommands
from door_fsm.supervisor import SupervisedRobot, Supervisor
from door_robot.crouch import walking_height
from door_robot.errors import RobotModelError
from door_robot.profile import load_profile

__all__ = ["FsmSupervisorNode", "main"]

HEARTBEAT_PERIOD_S = 0.25  # 4 Hz: the sim bridge's dead-man stops the robot when this heartbeat falls silent


class FsmSupervisorNode(Node):
    def __init__(self) -> None:
        super().__init__(NODE_NAME)
        p = self.parameters = declare_parameters(self, SUPERVISOR_PARAMETERS)
        with as_parameter_error(f"parameter 'robot_profile' = {p['robot_profile']!r}", RobotModelError):
            robot = SupervisedRobot.of(load_profile(p["robot_profile"]))
        self.steady = Clock(clock_type=ClockType.STEADY_TIME)
        with as_parameter_error("fsm_supervisor timeouts", MachineOptionsError):
            self.core = Supervisor.from_parameters(p, robot, self._now().wall)
        self.heartbeat = Heartbeat(self, period_s=HEARTBEAT_PERIOD_S)
        self._handlers: dict[type, Callable[[Any], object]] = {
            act.AnnounceState: self._announce, act.AskApproval: self._ask, act.StopMotion: self._stop,
            act.ClearApproval: lambda a: self.pubs[Topics.APPROVAL_REQUEST].publish(String(data="")),
            act.Notice: lambda a: self.get_logger().warning(a.text),
            act.RequestFootsteps: self._request, act.RequestMotion: self._request,
            act.CancelPlanning: lambda a: self.pubs[PLANNER_TOPICS[a.kind].cancel].publish(
                String(data=encode(PlanningCancel(a.request_id, a.reason)))),
            act.CallGrasp: self._call_grasp, act.Execute: self._execute,
            act.Look: lambda a: self.commands.send(a.trajectory),  # the head search's: no outcome awaited
            act.EndLook: lambda a: self.commands.hold_arm()}
        self.pubs = {topic: create_contract_publisher(self, topic) for topic in (
            Topics.TASK_STATE, Topics.APPROVAL_REQUEST, Topics.TASK_REPORT, Topics.WALK_CROUCH,
            *(t for topics in PLANNER_TOPICS.values() for t in (topics.request, topics.cancel)))}
        self.commands = RobotCommands(self)
        self._subscribe()
        self.grasp_clients = {side: self.create_client(spec.srv_class(), spec.name, qos_profile=spec.qos.to_profile())
                              for side, spec in robot.grasp_services().items()}
        self.create_timer(0.1, self._tick, clock=self.steady)  # runs even when /clock stops
        self.get_logger().info(f"ready: {robot.name}, {p['opening']} door, {p['autonomy']}, {p['backend']}")

    def _subscribe(self) -> None:
        """Every input goes to the core with the time now; a bad one comes back as a Notice."""
        core = self.core

        def feed(topic: TopicSpec, take: Callable[[Any, Instant], list[act.Action]], text: bool = True) -> None:
            create_contract_subscription(self, topic, lambda msg: self._run(take(msg.data if text else msg,
                                                                                 self._now())))
        for kind, topics in PLANNER_TOPICS.items():
            feed(topics.proposal, partial(core.proposal, kind), text=False)
            feed(topics.outcome, partial(core.planning_outcome, kind))
        feed(Topics.DOOR_ESTIMATE, core.door_estimate)
        feed(Topics.EXECUTION_OUTCOME, core.execution_outcome)
        feed(Topics.OPERATOR, self._operator)
        create_contract_subscription(self, Topics.HEAD_LOOK, lambda msg: self._run(core.look(msg)))

    def _now(self) -> Instant:
        return Instant(self.steady.now().nanoseconds * 1e-9, self.get_clock().now().nanoseconds * 1e-9)

    def _operator(self, text: str, now: Instant) -> list[act.Action]:
        self.get_logger().info(f"operator: {text.strip()}")
        return self.core.operator(text, now)

    def _feed(self, event: ev.Event) -> None:
        self._run(self.core.handle(event, self._now()))

    def _run(self, actions: list[act.Action]) -> None:
        for action in actions:
            self._handlers[type(action)](action)
        self.core.settle()

    def _tick(self) -> None:
        step, actions = self.core.tick(self._now(), set(self.get_node_names()))
        self.heartbeat.update(self.heartbeat.health, step.message or self.heartbeat.message,
                              watching=",".join(sorted(self.core.graph.seen)))
        if step.warning:
            self.get_logger().warning(step.warning)
        self._run(actions)

    # ------------------------------------------------------------------ actions
    def _announce(self, action: act.AnnounceState) -> None:
        label = action.state.label
        self.pubs[Topics.TASK_STATE].publish(String(data=label))
        self.heartbeat.update(Health.ERROR if action.state is TaskState.FAILED else Health.OK, label,
                              reason=action.reason or "-", failure=self.core.machine.failure_reason or "-")
        self.get_logger().info(f"state {label}" + (f" ({action.reason})" if action.reason else ""))
        clock = "sim" if self.get_parameter("use_sim_time").value else "wall"
        if (report := self.core.report(clock)) is not None:
            self.pubs[Topics.TASK_REPORT].publish(String(data=encode(report)))

    def _ask(self, action: act.AskApproval) -> None:
        self.pubs[Topics.APPROVAL_REQUEST].publish(String(data=action.text))
        self.get_logger().info(f"waiting for the operator: {action.text}")

    def _request(self, action: act.RequestFootsteps | act.RequestMotion) -> None:
        if isinstance(action, act.RequestFootsteps):  # the walk's crouch is set before its plan can exist
            crouch = self.core.walk_crouch(action)
            self.pubs[Topics.WALK_CROUCH].publish(Float64(data=crouch))
            if crouch != 0.0:
                self.get_logger().info(f"the walk {action.goal} goes {walking_height(crouch)} "
                                       "(the profile's crouch for this door and walk)")
        kind, request = self.core.request(action)
        self.pubs[PLANNER_TOPICS[kind].request].publish(String(data=encode(request)))

    def _stop(self, action: act.StopMotion) -> None:
        self.commands.stop()
        self.get_logger().warning(f"stopping all motion: {action.reason}")

    def _call_grasp(self, action: act.CallGrasp) -> None:
        hand, problem = self.core.grasp_hand()
        client = self.grasp_clients.get(hand)
        if problem or client is None or not client.service_is_ready():
            return self._feed(ev.GraspAnswered(action.request_id, False, problem or f"/{hand}_hand/grasp is not available"))
        future = client.call_async(SetBool.Request(data=action.close))
        future.add_done_callback(lambda f, rid=action.request_id: self._feed(ev.GraspAnswered.of_response(rid, f.result())))

    def _execute(self, action: act.Execute) -> None:
        stamp = self.commands.next_stamp()
        message = self.core.take(action.request_id, stamp)
        if message is None:
            return self._feed(ev.ExecutionFinished(action.request_id, False, "the approved proposal is gone"))
        self.commands.send(message, stamp)


main = node_main(FsmSupervisorNode, __name__)
