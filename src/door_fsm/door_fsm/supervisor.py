"""The supervisor without ROS: the machine, its bookkeeping and the robot, between messages.

:class:`Supervisor` is what ``/fsm_supervisor`` does with what it hears: the JSON payloads and
operator words of its topics become machine events (:mod:`door_fsm.answers`), the answers are
paired with their requests (:mod:`door_fsm.exchange`), the door's context is kept
(:mod:`door_fsm.door_context`) and the graph watched (:mod:`door_fsm.graph_watch`). Every input
returns the machine's actions, for the node to perform; after performing them the node calls
:meth:`Supervisor.settle` (answers to older requests are stale from then on). Bad input (a
payload that does not decode, an estimate no planner can use, an unknown operator command)
changes nothing and returns one :class:`~door_fsm.actions.Notice` saying why.

What it needs of the robot comes from its profile (:class:`SupervisedRobot`): which hands it
has (the arm chains; a door whose grasp hand the robot lacks fails the grasp, saying so) and
how long a footstep takes (a walk's nominal duration, which scales its execution deadline).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from door_contract.converters.trajectory import msg_to_joint_path
from door_contract.errors import ContractError
from door_contract.payloads import (
    ExecutionOutcome,
    FootstepRequest,
    MotionRequest,
    OutcomeStatus,
    PlanningOutcome,
    TaskReport,
    decode,
)
from door_contract.stamps import stamp_ns
from door_contract.topics import Services, ServiceSpec
from door_contract.vocabulary import Autonomy, Backend, DoorOpening, PlannerKind, Side, TaskState
from door_fsm import actions as act
from door_fsm import events as ev
from door_fsm.answers import execution_event, planning_event, usable_door_estimate
from door_fsm.door_context import DoorContext
from door_fsm.exchange import PlanExchange, Proposal
from door_fsm.graph_watch import GraphStep, GraphWatch
from door_fsm.machine import DoorTaskMachine, MachineOptions
from door_fsm.operator_commands import UnknownCommandError, parse_command
from door_fsm.records import Instant
from door_fsm.states import Phase
from door_fsm.summaries import door_summary, task_report, work_of
from door_robot.crouch import CrouchRules
from door_robot.profile import RobotProfile

__all__ = ["GRASP_SERVICES", "SupervisedRobot", "Supervisor"]

GRASP_SERVICES: dict[Side, ServiceSpec] = {Side.LEFT: Services.LEFT_GRASP, Side.RIGHT: Services.RIGHT_GRASP}
"""The grasp service of each hand."""


@dataclass(frozen=True)
class SupervisedRobot:
    """What the supervisor knows of the robot (from its profile): its name, its time per
    footstep (s, robot clock) and the joints of each arm chain, by side (a look may not move
    them; an approach's joints say which hand it moves; a side with a chain has a hand)."""

    name: str
    step_duration: float
    arms: tuple[tuple[Side, frozenset[str]], ...]
    crouch: CrouchRules = CrouchRules()  # how low it walks (its profile's; the default: upright)

    @classmethod
    def of(cls, profile: RobotProfile) -> SupervisedRobot:
        arms = tuple((Side(side), frozenset(arm.joints)) for side, arm in profile.arms.items())
        return cls(profile.name, profile.walking.step_duration, arms, profile.crouch)

    @property
    def hands(self) -> frozenset[Side]:
        """The sides with an arm chain."""
        return frozenset(side for side, _ in self.arms)

    @property
    def arm_joints(self) -> frozenset[str]:
        """Every joint of every arm chain (TALOS's torso included)."""
        return frozenset().union(*(joints for _, joints in self.arms))

    def arm_of(self, joint_names: Sequence[str]) -> Side | None:
        """The arm a trajectory over ``joint_names`` moves: the one whose own joints (not shared
        with another arm, as the torso is) it names; None when none or both."""
        named = set(joint_names)
        moved = [side for side, joints in self.arms
                 if named & (joints - frozenset().union(*(other for s, other in self.arms if s is not side)))]
        return moved[0] if len(moved) == 1 else None

    def grasp_services(self) -> dict[Side, ServiceSpec]:
        """The grasp services of the robot's hands."""
        return {side: spec for side, spec in GRASP_SERVICES.items() if side in self.hands}


def look_problem(trajectory: Any, arm_joints: frozenset[str]) -> str:
    """Why a look (a JointTrajectory) must not reach the robot, or "": no joints, a trajectory
    the contract's converter refuses (:func:`~door_contract.converters.trajectory.msg_to_joint_path`:
    no points, positions that do not match the joints, non-finite values, times not
    increasing), or an arm joint (the torso's included: a head search moves the neck only)."""
    if not trajectory.joint_names:
        return "no joints"
    moved_arm = sorted(set(trajectory.joint_names) & arm_joints)
    if moved_arm:
        return f"it moves {', '.join(moved_arm)} (a look moves the neck only)"
    try:
        msg_to_joint_path(trajectory)
    except ContractError as error:
        return str(error)
    return ""


class Supervisor:
    def __init__(self, options: MachineOptions, backend: Backend, robot: SupervisedRobot, graph: GraphWatch) -> None:
        self.machine = DoorTaskMachine(options)
        self.door = DoorContext(options.opening, backend)
        self.robot, self.graph = robot, graph
        self.exchange = PlanExchange(lambda message: work_of(message, robot.step_duration))
        self._detection_request: int | None = None
        self._looked = False  # a look was sent since the detection request

    @classmethod
    def from_parameters(cls, p: Mapping[str, Any], robot: SupervisedRobot, wall_now: float) -> Supervisor:
        """The supervisor of the node's parameters (``door_fsm.parameters``), started at wall
        time ``wall_now`` (s); :class:`MachineOptionsError` names a bad option."""
        options = MachineOptions(
            opening=DoorOpening(p["opening"]), autonomy=Autonomy(p["autonomy"]),
            planning_timeout_s=p["planning_timeout"], approval_timeout_s=p["approval_timeout"],
            execution_factor=p["execution_timeout_factor"], execution_margin_s=p["execution_timeout_margin"],
            max_repeats=p["max_repeats"])
        graph = GraphWatch(set(p["required_nodes"]), wall_now + p["start_delay"], p["graph_timeout"])
        return cls(options, Backend(p["backend"]), robot, graph)

    # ------------------------------------------------------------------ inputs → actions
    def door_estimate(self, text: str, now: Instant) -> list[act.Action]:
        """A ``/door/estimate`` payload. While DETECT_DOOR waits, the estimate is its proposal and
        the one every later request names."""
        try:
            estimate = usable_door_estimate(text)
        except ContractError as error:
            return [act.Notice(f"door estimate rejected: {error}")]
        self.door.latest = estimate
        if self._detection_request is None:
            return []
        request, self._detection_request = self._detection_request, None
        self.door.approved = estimate
        search_over: list[act.Action] = [act.EndLook()] if self._looked else []
        self._looked = False
        return search_over + self.handle(ev.ProposalReady(request, door_summary(estimate)), now)

    def look(self, trajectory: Any) -> list[act.Action]:
        """The detector's neck move (``/door_detector/look``): sent to the robot only while
        DETECT_DOOR waits for an estimate (not paused, stopped or in any other state), and only
        a well-formed one that moves no arm (:func:`look_problem`; else a notice, nothing moves).
        The estimate that confirms the door ends the search: a look still moving is stopped
        (:class:`~door_fsm.actions.EndLook`), or the walk would find the robot busy with it.
        Likewise a look replaces the one before it, which is stopped first: the robot refuses a
        trajectory while another runs, and the search, which moves on once the neck is within
        a few hundredths of a radian of a view, asks for the next view while the last move's
        tail still runs (a Monte-Carlo door was never confirmed: every second view was refused
        as busy, the head never turned towards the door)."""
        waiting = (self.machine.state is TaskState.DETECT_DOOR and self.machine.phase is Phase.PLANNING
                   and self._detection_request == self.machine.request_id)
        if not waiting:
            return []
        problem = look_problem(trajectory, self.robot.arm_joints)
        if problem:
            return [act.Notice(f"look refused: {problem}")]
        replaced: list[act.Action] = [act.EndLook()] if self._looked else []
        self._looked = True
        return replaced + [act.Look(trajectory)]

    def proposal(self, kind: PlannerKind, message: Any, now: Instant) -> list[act.Action]:
        """A planner's proposal message (a Path or JointTrajectory), known by its stamp."""
        return self._answer(self.exchange.add_message(kind, stamp_ns(message.header.stamp), message), now)

    def planning_outcome(self, kind: PlannerKind, text: str, now: Instant) -> list[act.Action]:
        """A planner's PlanningOutcome payload."""
        try:
            outcome = decode(PlanningOutcome, text)
        except ContractError as error:
            return [act.Notice(f"planning outcome rejected: {error}")]
        return self._answer(self.exchange.add_outcome(kind, outcome), now)

    def execution_outcome(self, text: str, now: Instant) -> list[act.Action]:
        """The robot's ExecutionOutcome payload; executions not sent by this supervisor are ignored."""
        try:
            outcome = decode(ExecutionOutcome, text)
        except ContractError as error:
            return [act.Notice(f"execution outcome rejected: {error}")]
        request = self.exchange.finished(outcome.request_id)
        if request is None:
            return []
        if outcome.status is OutcomeStatus.SUCCESS and not outcome.slipped:
            self.door.executed()
        return self.handle(execution_event(outcome, request), now)

    def operator(self, text: str, now: Instant) -> list[act.Action]:
        """An operator's words."""
        try:
            word = parse_command(text)
        except UnknownCommandError as error:
            return [act.Notice(str(error))]
        return self.handle(ev.OperatorSaid(word), now)

    def tick(self, now: Instant, present: set[str]) -> tuple[GraphStep, list[act.Action]]:
        """Every 0.1 s with the nodes in the graph: start the task, report lost nodes, deadlines."""
        step = self.graph.step(now.wall, present)
        actions = self._keep(self.machine.start(now)) if step.start else []
        for name in step.lost:
            actions += self.handle(ev.NodeLost(name), now)
        if self.graph.started:
            actions += self._keep(self.machine.tick(now))
        return step, actions

    def handle(self, event: ev.Event, now: Instant) -> list[act.Action]:
        """The machine's actions for ``event`` (e.g. a grasp's answer)."""
        return self._keep(self.machine.handle(event, now))

    def _keep(self, actions: list[act.Action]) -> list[act.Action]:
        """``actions`` but a detection request, which is kept here: the detector answers on its
        own, its next usable estimate is the proposal."""
        for action in actions:
            if isinstance(action, act.RequestDetection):
                self._detection_request = action.request_id
        return [action for action in actions if not isinstance(action, act.RequestDetection)]

    def settle(self) -> None:
        """The actions are performed: answers to requests older than the current one are stale."""
        self.exchange.begin(self.machine.request_id)

    # ------------------------------------------------------------------ what the node sends
    def request(self, action: act.RequestFootsteps | act.RequestMotion
                ) -> tuple[PlannerKind, FootstepRequest | MotionRequest]:
        """The planner and the request payload of ``action``."""
        if isinstance(action, act.RequestFootsteps):
            return PlannerKind.FOOTSTEPS, self.door.footstep_request(action)
        return PlannerKind.MOTION, self.door.motion_request(action)

    def walk_crouch(self, action: act.RequestFootsteps) -> float:
        """How far below its standing height the robot walks the plan ``action`` asks for (m):
        the lowest of its profile's crouches (:class:`~door_robot.crouch.CrouchRules`: every
        walk's, a push passage's whose lever meets the pelvis, the walk to a door whose lever is
        low), the lever's height and the door's width the approved estimate's (``odom``'s z is
        the floor's height)."""
        door = self.door.approved
        lever_and_width = (door.handle_position[2], door.width) if door is not None else None
        return self.robot.crouch.for_walk(action.goal, self.door.opening, lever_and_width)

    def grasp_hand(self) -> tuple[Side, str]:
        """The hand that opens this door, and why it cannot ("" if it can)."""
        hand = self.door.grasp_hand()
        if hand not in self.robot.hands:
            return hand, f"{self.robot.name} has no {hand} hand (its profile's arms: " \
                         f"{', '.join(sorted(self.robot.hands)) or 'none'})"
        return hand, ""

    def take(self, request_id: int, stamp_ns: int) -> Any | None:
        """The approved proposal's message, to send stamped ``stamp_ns`` (None: it is gone)."""
        proposal = self.exchange.take(request_id)
        if proposal is None:
            return None
        self.exchange.sent(stamp_ns, request_id)
        return proposal.message

    def report(self, robot_clock: str) -> TaskReport | None:
        """The TaskReport once the task has ended (``robot_clock``: "sim" or "wall"), else None."""
        end = self.machine.state.end
        if end is None:
            return None
        return task_report(end, self.machine.failure_reason, self.door.opening, self.machine.options.autonomy,
                           self.machine.report(), robot_clock)

    def _answer(self, answer: Proposal | PlanningOutcome | None, now: Instant) -> list[act.Action]:
        if answer is None:
            return []
        if isinstance(answer, Proposal):
            self.door.planned(answer.outcome)
            if self.machine.state is TaskState.MOVE_TO_HANDLE:  # the optimiser chose the hand
                self.door.approach_hand = self.robot.arm_of(getattr(answer.message, "joint_names", ()))
        return self.handle(planning_event(answer), now)
