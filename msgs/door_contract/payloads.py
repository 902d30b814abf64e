"""JSON payloads carried in ``std_msgs/String`` between nodes (requests, outcomes, estimates).

Every payload is a frozen dataclass; :func:`encode` / :func:`decode` convert it, and
decoding rejects missing fields, unknown fields and wrong types with a
:class:`~door_contract.errors.ContractError` — a malformed message never reaches a core.
"""

from __future__ import annotations

import dataclasses
import json
import math
import types
import typing
from enum import Enum
from typing import Any, TypeVar, get_type_hints

from door_contract.errors import ContractError, NonFiniteError
from door_contract.json_text import parse_bounded
from door_contract.vocabulary import (
    Autonomy,
    Backend,
    DetectionMode,
    DoorOpening,
    HingeSide,
    Motion,
    Side,
    TaskEnd,
    WalkGoal,
)

Payload = TypeVar("Payload")


class OutcomeStatus(str, Enum):
    SUCCESS = "success"
    FAILURE = "failure"
    REJECTED = "rejected"  # refused before doing anything (bad input); nothing moved
    SUPERSEDED = "superseded"  # planning only: a newer request or a cancel replaced it; nothing proposed
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
class PlanningOutcome:
    """Published by a planner for every request id: success (with figures) or the reason."""

    request_id: int
    status: OutcomeStatus
    reason: str = ""
    planning_time_s: float = 0.0
    details: dict = dataclasses.field(default_factory=dict)


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


@dataclasses.dataclass(frozen=True)
class TaskReport:
    """``/door_task/report`` (latched): how the task ended and every state attempt."""

    final_state: TaskEnd
    failure_reason: str
    opening: DoorOpening
    autonomy: Autonomy
    attempts: tuple[dict, ...]  # door_fsm.records.StateRecord.as_dict(): state, attempt, outcome, times, summary
    clocks: str = ""  # which clock each time is measured on (docs/CLOCKS.md)


def encode(payload: Any) -> str:
    """JSON text of a payload dataclass (Enums by value)."""
    return json.dumps(dataclasses.asdict(payload), default=_enum_value, allow_nan=False)


def without_non_finite(value: Any) -> Any:
    """``value`` with every NaN or infinity (in nested dicts, lists, tuples) replaced by None.

    A failure's figures (the cost of a diverged plan) may be NaN; the outcome must still go
    out (``encode`` refuses NaN, which once killed the optimiser: issue #12).
    """
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {k: without_non_finite(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [without_non_finite(v) for v in value]
    return value


def _enum_value(value: Any) -> Any:
    if isinstance(value, Enum):
        return value.value
    raise TypeError(f"cannot encode {type(value).__name__}")


def decode(payload_type: type[Payload], text: str) -> Payload:
    """A ``payload_type`` instance from JSON, or :class:`ContractError` saying what is wrong
    (size and nesting are bounded before parsing: :func:`~door_contract.json_text.parse_bounded`)."""
    document = parse_bounded(payload_type.__name__, text)
    if not isinstance(document, dict):
        raise ContractError(f"{payload_type.__name__}: expected a JSON object")
    hints = get_type_hints(payload_type)
    fields = {f.name: f for f in dataclasses.fields(payload_type)}  # type: ignore[arg-type]  # Payload: any dataclass
    unknown = sorted(set(document) - set(fields))
    if unknown:
        raise ContractError(f"{payload_type.__name__}: unknown field(s) {', '.join(unknown)}")
    values = {name: _field_value(payload_type.__name__, name, hints[name], document[name])
              for name in fields if name in document}
    try:
        return payload_type(**values)
    except TypeError as error:
        raise ContractError(f"{payload_type.__name__}: {error}") from None


def _optional_type(hint: Any) -> Any:
    """``X`` of a hint ``X | None``, else None."""
    arguments = typing.get_args(hint)
    if typing.get_origin(hint) in (typing.Union, types.UnionType) and len(arguments) == 2 and type(None) in arguments:
        return next(argument for argument in arguments if argument is not type(None))
    return None


def _finite_tuple(owner: str, name: str, values: list[Any]) -> tuple[Any, ...]:
    items: list[Any] = []
    for value in values:
        if isinstance(value, list):
            items.append(_finite_tuple(owner, name, value))
        elif isinstance(value, dict):
            items.append(value)
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            if not math.isfinite(value):
                raise NonFiniteError(f"{owner}.{name} is not finite")
            items.append(float(value))
        else:
            raise ContractError(f"{owner}.{name}: expected numbers, got {value!r}")
    return tuple(items)


def _field_value(owner: str, name: str, hint: Any, value: Any) -> Any:
    optional = _optional_type(hint)
    if optional is not None:
        return None if value is None else _field_value(owner, name, optional, value)
    if isinstance(hint, type) and issubclass(hint, Enum):
        if issubclass(hint, str) and not isinstance(value, str):
            raise ContractError(f"{owner}.{name}: expected a string, got {value!r}")
        try:
            return hint(value)
        except ValueError:
            allowed = ", ".join(str(m.value) for m in hint)
            raise ContractError(f"{owner}.{name}: unknown {name} {value!r}; use one of {allowed}") from None
    if hint is float:
        if not isinstance(value, (int, float)) or isinstance(value, bool):
            raise ContractError(f"{owner}.{name}: expected a number, got {value!r}")
        if not math.isfinite(value):
            raise NonFiniteError(f"{owner}.{name} is not finite")
        return float(value)
    if hint is int and (not isinstance(value, int) or isinstance(value, bool)):
        raise ContractError(f"{owner}.{name}: expected an integer, got {value!r}")
    if hint is bool and not isinstance(value, bool):
        raise ContractError(f"{owner}.{name}: expected true or false, got {value!r}")
    if hint is str and not isinstance(value, str):
        raise ContractError(f"{owner}.{name}: expected a string, got {value!r}")
    if getattr(hint, "__origin__", None) is tuple or hint is tuple:
        if not isinstance(value, list):
            raise ContractError(f"{owner}.{name}: expected a list, got {value!r}")
        return _finite_tuple(owner, name, value)
    return value
