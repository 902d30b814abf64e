"""JSON payloads carried in ``std_msgs/String`` between nodes (requests, outcomes, estimates).

Every payload is a frozen dataclass; :func:`encode` / :func:`decode` convert it, and
decoding rejects missing fields, unknown fields and wrong types with a
:class:`~door_contract.errors.ContractError` — a malformed message never reaches a core.
An enum member is spelled by its value, a :class:`~door_contract.vocabulary.TaskState` by its
label (as ``/door_task/state`` publishes it), in both directions.
"""

from __future__ import annotations

import dataclasses
import functools
import json
import math
import types
import typing
from enum import Enum
from typing import Any, TypeVar, get_type_hints

from door_contract.errors import ContractError, NonFiniteError
from door_contract.json_text import parse_bounded
from door_contract.vocabulary import (
    AttemptOutcome,
    Autonomy,
    Backend,
    DetectionMode,
    DoorOpening,
    HingeSide,
    Motion,
    Side,
    TaskEnd,
    TaskState,
    WalkGoal,
)

__all__ = ["DoorEstimate", "ExecutionKind", "ExecutionOutcome", "FootstepFigures", "FootstepRequest", "MotionFigures",
           "MotionRequest", "OutcomeStatus", "PlanningCancel", "PlanningOutcome", "ProposalSummary", "StateAttempt",
           "TaskReport", "decode", "decode_document", "encode", "encode_document", "finite_or_none"]

Payload = TypeVar("Payload")


class OutcomeStatus(str, Enum):
    SUCCESS = "success"
    FAILURE = "failure"
    REJECTED = "rejected"  # refused before doing anything (bad input); nothing moved
    SUPERSEDED = "superseded"  # planning only: a newer request or a cancel replaced it; nothing proposed
    SKIPPED = "skipped"  # planning only: nothing to do for this door (a narrow push door's doorway walk); nothing proposed
    STOPPED = "stopped"  # execution only: stopped on command (empty message, lost supervisor); the robot holds
    FELL = "fell"  # execution only: the robot fell; it stays down, the task cannot go on


class ExecutionKind(str, Enum):
    TRAJECTORY = "trajectory"
    FOOTSTEPS = "footsteps"


@dataclasses.dataclass(frozen=True)
class ExecutionOutcome:
    """Published by the sim bridge when a trajectory or footstep plan ends or is rejected.

    ``request_id`` is the ``header.stamp`` (ns) of the executed JointTrajectory or Path:
    the FSM stamps what it sends and matches the outcome by it.
    """

    kind: ExecutionKind
    request_id: int
    status: OutcomeStatus
    reason: str = ""
    duration_s: float = 0.0
    slipped: bool = False  # the hand slipped off the handle during this trajectory


@dataclasses.dataclass(frozen=True)
class FootstepFigures:
    """What a footstep search reports: the A* node expansions it took and, with a plan, its
    steps and the walked length (m)."""

    expansions: int
    steps: int = 0
    length_m: float = 0.0


@dataclasses.dataclass(frozen=True)
class MotionFigures:
    """What a motion plan reports, converged or not: its cost and largest constraint violation
    (None when not finite: a diverged plan's outcome must still go out, issue #12), the solver's
    iterations, the initial guesses tried, the trajectory's duration (s) and the backend; with a
    trajectory, the arm chain's joint names, its initial guess and the optimised trajectory
    (rad, one row per waypoint) for the report's before/after plot ([Zucker 2013] Fig. 4)."""

    cost: float | None
    max_violation: float | None
    iterations: int
    attempts: int  # initial guesses tried
    duration_s: float
    backend: Backend
    joint_names: tuple[str, ...] = ()
    initial_guess: tuple[tuple[float, ...], ...] = ()
    optimised: tuple[tuple[float, ...], ...] = ()


@dataclasses.dataclass(frozen=True)
class PlanningOutcome:
    """Published by a planner for every request id: success (with figures) or the reason.

    ``stamp_ns`` is the ``header.stamp`` (ns) of the proposal (Path or JointTrajectory) this
    outcome goes with, -1 when nothing was proposed: the FSM pairs the two by it. A motion plan
    says the hinge angle it leaves the door at (``door_angle``, rad; None: no plan, or not
    finite). Each planner's figures are in its own field, the other one is None.
    """

    request_id: int
    status: OutcomeStatus
    reason: str = ""
    planning_time_s: float = 0.0
    stamp_ns: int = -1
    door_angle: float | None = None
    footsteps: FootstepFigures | None = None
    motion: MotionFigures | None = None


@dataclasses.dataclass(frozen=True)
class DoorEstimate:
    """Published on ``/door/estimate`` (latched) by the detector; positions in ``frame_id``.

    ``normal`` is the door plane's unit normal pointing towards the robot; ``corners`` are
    bottom-hinge, bottom-free, top-free, top-hinge (m); ``handle_position`` is the grasp point.
    """

    stamp: float  # s
    frame_id: str
    handle_position: tuple[float, float, float]
    normal: tuple[float, float, float]
    hinge_side: HingeSide
    width: float  # m
    corners: tuple[tuple[float, float, float], ...]
    confidence: float  # 0..1, fraction of voting frames that agreed
    frames_voted: int
    mode: DetectionMode


@dataclasses.dataclass(frozen=True)
class FootstepRequest:
    """``/footstep_planner/request``: plan to the stand pose or through the door.

    ``door_angle`` is the current hinge angle (rad, 0 = closed, > 0 open), as known to the
    FSM from the last executed door motion; the passage is re-planned when it changes.
    """

    request_id: int
    goal: WalkGoal
    opening: DoorOpening
    door_angle: float = 0.0
    door_stamp: float = -1.0  # the approved DoorEstimate's stamp; < 0: the latest estimate
    door: str = ""  # the approved DoorEstimate itself (JSON), so a late-joining planner has it
    attempt: int = 0  # 0 first try, +1 per repeat of the FSM state: a repeat searches with a larger budget


@dataclasses.dataclass(frozen=True)
class MotionRequest:
    """``/trajectory_optimizer/request``: one motion of the door motion library."""

    request_id: int
    motion: Motion
    opening: DoorOpening
    backend: Backend | None = None  # None: the node's parameter
    door_angle: float = 0.0
    door_stamp: float = -1.0  # the approved DoorEstimate's stamp; < 0: the latest estimate
    door: str = ""  # the approved DoorEstimate itself (JSON), so a late-joining planner has it
    attempt: int = 0  # 0 first try, +1 per repeat of the FSM state: a repeat may use other guesses
    hand: Side | None = None  # the grasping hand, once an approach chose it; None: the optimiser picks it


@dataclasses.dataclass(frozen=True)
class PlanningCancel:
    """``/<planner>/cancel``: drop request ``request_id`` (queued or running); it is answered
    SUPERSEDED and its result, if any, is never proposed."""

    request_id: int
    reason: str = ""


ProposalSummary = dict[str, str | float | int]
"""What the operator is shown of a proposal, figure by figure (``steps``, ``cost``,
``planning_ms``, a door estimate's ``width_m``, ...): the approval request's text and a state
attempt's record of it.

Deliberately an open mapping, not typed dataclasses: it is a rendering of figures that are
typed where they are read (:class:`DoorEstimate`, :class:`FootstepFigures`,
:class:`MotionFigures`, built by ``door_fsm.summaries``), nothing reads a figure back out of
it, and what it holds is shown in insertion order and stored as a flat JSON object that old
``trial.json`` files must still decode to. A union of summary classes would repeat those
figures and need a union, flattened encoding and a key-guessing decoder in this codec, for no
change an operator or a report could see."""


@dataclasses.dataclass(frozen=True)
class StateAttempt:
    """One attempt at one state of the task, as the TaskReport lists it (times in s).

    ``state`` is spelled by its label in JSON (``OPEN_DOOR/TURN_HANDLE`` for a sub-state: its
    phase first), as ``/door_task/state`` publishes it and old ``report.json`` / ``trial.json``
    files hold it; ``attempt`` is 1 for the first try. Planning and waiting for the operator are
    measured on the wall clock, moving on the robot clock (``TaskReport.clocks``); ``robot_s`` is
    the attempt from entry to outcome on the robot clock (0 while unfinished, and in reports
    written before it existed).
    """

    state: TaskState
    attempt: int
    outcome: AttemptOutcome
    planning_s: float = 0.0
    waiting_s: float = 0.0
    moving_s: float = 0.0
    reason: str = ""
    summary: ProposalSummary = dataclasses.field(default_factory=dict)
    robot_s: float = 0.0


@dataclasses.dataclass(frozen=True)
class TaskReport:
    """``/door_task/report`` (latched): how the task ended and every state attempt."""

    final_state: TaskEnd
    failure_reason: str
    opening: DoorOpening
    autonomy: Autonomy
    attempts: tuple[StateAttempt, ...]
    clocks: str = ""  # which clock each time is measured on (docs/CLOCKS.md)


def encode(payload: Any) -> str:
    """JSON text of a payload dataclass (nested dataclasses as objects, enum members by their
    spelling: :func:`_spelling`)."""
    return json.dumps(dataclasses.asdict(payload), default=_json_spelling, allow_nan=False)


def encode_document(payload: Any) -> dict[str, Any]:
    """The JSON object of a payload dataclass as plain data (what :func:`encode` writes and
    :func:`decode_document` reads back), for a file that embeds payloads: ``report.json``'s
    and ``trial.json``'s attempts."""
    document: dict[str, Any] = json.loads(encode(payload))
    return document


def finite_or_none(value: float) -> float | None:
    """``value``, or None when it is NaN or infinite.

    A failure's figures (the cost of a diverged plan) may be NaN; the outcome must still go
    out (``encode`` refuses NaN, which once killed the optimiser: issue #12).
    """
    return value if math.isfinite(value) else None


def _spelling(member: Enum) -> Any:
    """How a payload spells an enum member: a task state by its label (``OPEN_DOOR/TURN_HANDLE``,
    as ``/door_task/state`` publishes it), any other member by its value."""
    return member.label if isinstance(member, TaskState) else member.value


def _json_spelling(value: Any) -> Any:
    """``json.dumps``'s fallback: an enum member that is no str (a str enum is written as its
    value by json itself; a TaskState is not one, so it reaches here)."""
    if isinstance(value, Enum):
        return _spelling(value)
    raise TypeError(f"cannot encode {type(value).__name__}")


def decode(payload_type: type[Payload], text: str) -> Payload:
    """A ``payload_type`` instance from JSON, or :class:`ContractError` saying what is wrong
    (size and nesting are bounded before parsing: :func:`~door_contract.json_text.parse_bounded`)."""
    return decode_document(payload_type, parse_bounded(payload_type.__name__, text))


def decode_document(payload_type: type[Payload], document: Any, owner: str = "") -> Payload:
    """A ``payload_type`` instance from parsed JSON (a dict, e.g. read back from a report file),
    checked as :func:`decode` checks text; ``owner`` names it in errors (default: the type)."""
    owner = owner or payload_type.__name__
    if not isinstance(document, dict):
        raise ContractError(f"{owner}: expected a JSON object")
    hints = get_type_hints(payload_type)
    names = [f.name for f in dataclasses.fields(payload_type)]  # type: ignore[arg-type]  # Payload: any dataclass
    unknown = sorted(set(document) - set(names))
    if unknown:
        raise ContractError(f"{owner}: unknown field(s) {', '.join(unknown)}")
    values = {name: _field_value(owner, name, hints[name], document[name]) for name in names if name in document}
    try:
        return payload_type(**values)
    except TypeError as error:
        raise ContractError(f"{owner}: {error}") from None


def _optional_type(hint: Any) -> Any:
    """``X`` of a hint ``X | None``, else None."""
    arguments = typing.get_args(hint)
    if typing.get_origin(hint) in (typing.Union, types.UnionType) and len(arguments) == 2 and type(None) in arguments:
        return next(argument for argument in arguments if argument is not type(None))
    return None


def _item_type(hint: Any) -> Any:
    """The type of a tuple hint's items: ``X`` of ``tuple[X, ...]`` or ``tuple[X, X, X]``.

    Lengths are the consumer's to check (:func:`~door_contract.door_estimates.door_estimate_problem`
    names a door's malformed corners); a payload tuple holds items of one type.
    """
    kinds = {argument for argument in typing.get_args(hint) if argument is not Ellipsis}
    if len(kinds) != 1:
        raise TypeError(f"{hint}: a payload tuple names the one type of its items")
    return kinds.pop()


def _tuple_value(owner: str, name: str, hint: Any, value: Any) -> tuple[Any, ...]:
    """A tuple from a JSON list, every item decoded as the hint's item type."""
    if not isinstance(value, list):
        raise ContractError(f"{owner}.{name}: expected a list, got {value!r}")
    item_type = _item_type(hint)
    return tuple(_field_value(owner, name, item_type, item) for item in value)


@functools.cache
def _members_by_spelling(hint: type[Enum]) -> dict[Any, Enum]:
    """Every member of ``hint`` by its :func:`_spelling` (the inverse of encoding it)."""
    return {_spelling(member): member for member in hint}


def _enum_member(owner: str, name: str, hint: type[Enum], value: Any) -> Enum:
    """The member of ``hint`` spelled ``value``, or ContractError listing the allowed spellings."""
    members = _members_by_spelling(hint)
    if all(isinstance(spelled, str) for spelled in members) and not isinstance(value, str):
        raise ContractError(f"{owner}.{name}: expected a string, got {value!r}")
    try:
        return members[value]
    except (KeyError, TypeError):  # TypeError: an unhashable value (a list, an object)
        allowed = ", ".join(str(spelled) for spelled in members)
        raise ContractError(f"{owner}.{name}: unknown {name} {value!r}; use one of {allowed}") from None


def _number(owner: str, name: str, value: Any) -> float:
    """A finite JSON number as a float (NonFiniteError for NaN and infinities)."""
    if not isinstance(value, (int, float)) or isinstance(value, bool):
        raise ContractError(f"{owner}.{name}: expected a number, got {value!r}")
    if not math.isfinite(value):
        raise NonFiniteError(f"{owner}.{name} is not finite")
    return float(value)


def _scalar_problem(hint: Any, value: Any) -> str:
    """What is wrong with ``value`` for an int, bool or str field ("" if nothing)."""
    if hint is int and (not isinstance(value, int) or isinstance(value, bool)):
        return "expected an integer"
    if hint is bool and not isinstance(value, bool):
        return "expected true or false"
    if hint is str and not isinstance(value, str):
        return "expected a string"
    return ""


def _field_value(owner: str, name: str, hint: Any, value: Any) -> Any:
    """``value`` (parsed JSON) checked and converted to the field's type ``hint``."""
    optional = _optional_type(hint)
    if optional is not None:
        return None if value is None else _field_value(owner, name, optional, value)
    if isinstance(hint, type) and issubclass(hint, Enum):
        return _enum_member(owner, name, hint, value)
    if hint is float:
        return _number(owner, name, value)
    problem = _scalar_problem(hint, value)
    if problem:
        raise ContractError(f"{owner}.{name}: {problem}, got {value!r}")
    if typing.get_origin(hint) is tuple:
        return _tuple_value(owner, name, hint, value)
    if isinstance(hint, type) and dataclasses.is_dataclass(hint):
        return decode_document(hint, value, f"{owner}.{name}")
    if typing.get_origin(hint) is dict and not isinstance(value, dict):
        raise ContractError(f"{owner}.{name}: expected a JSON object, got {value!r}")
    return value
