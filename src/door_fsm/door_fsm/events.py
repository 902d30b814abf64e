"""Events the supervisor feeds into the machine (converted from topics by the node)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from door_contract.payloads import ProposalSummary
from door_fsm.operator_commands import OperatorWord

__all__ = ["Event", "ExecutionFinished", "GraspAnswered", "HandSlipped", "NodeLost", "OperatorSaid", "ProposalFailed",
           "ProposalReady", "ProposalSkipped"]


@dataclass(frozen=True)
class ProposalReady:
    """A planner (or the detector) answered request ``request_id`` with a proposal."""

    request_id: int
    summary: ProposalSummary = field(default_factory=dict)  # shown to the operator: counts, costs, durations
    work_s: float = 0.0  # nominal execution time (trajectory duration, steps × step time), robot clock


@dataclass(frozen=True)
class ProposalFailed:
    request_id: int
    reason: str


@dataclass(frozen=True)
class ProposalSkipped:
    """A planner answered request ``request_id``: this door has nothing to do there (a narrow
    push door's doorway walk), and ``reason`` says why."""

    request_id: int
    reason: str


@dataclass(frozen=True)
class ExecutionFinished:
    """The sim bridge (or robot) finished — or rejected, or stopped — executing ``request_id``."""

    request_id: int
    succeeded: bool
    reason: str = ""
    fell: bool = False  # the robot fell: the task cannot go on (no repeat)


@dataclass(frozen=True)
class GraspAnswered:
    request_id: int
    succeeded: bool
    message: str = ""

    @classmethod
    def of_response(cls, request_id: int, response: Any) -> GraspAnswered:
        """From a SetBool response (``success``, ``message``), or None when the call got none."""
        if response is None:
            return cls(request_id, False, "no answer")
        return cls(request_id, bool(response.success), str(response.message))


@dataclass(frozen=True)
class HandSlipped:
    reason: str


@dataclass(frozen=True)
class OperatorSaid:
    word: OperatorWord


@dataclass(frozen=True)
class NodeLost:
    node_name: str


Event = (ProposalReady | ProposalFailed | ProposalSkipped | ExecutionFinished | GraspAnswered | HandSlipped
         | OperatorSaid | NodeLost)
