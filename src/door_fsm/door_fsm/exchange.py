"""Which proposal answers which request, and which execution is which: the FSM's bookkeeping
between its requests and the planners' and robot's answers, ROS-free.

A planner answers a request with two messages on two topics, in either order: the proposal
itself (a Path or JointTrajectory, stamped by the planner) and a PlanningOutcome naming the
request id and that stamp (``PlanningOutcome.stamp_ns``). :class:`PlanExchange` pairs them per
planner (``kind``), keeps the pair only for the request the machine waits on, hands the
message out exactly once (a second ``approve`` cannot execute it twice) and remembers the
stamp under which it was sent, so the robot's ExecutionOutcome finds its request.

Every table is bounded and a new request drops everything older (issue #17: proposals were
never evicted); unmatched messages age out first-in, first-out.
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Callable, Hashable
from dataclasses import dataclass
from typing import Any, TypeVar

from door_contract.payloads import OutcomeStatus, PlanningOutcome
from door_contract.vocabulary import PlannerKind

__all__ = ["PlanExchange", "Proposal"]


@dataclass(frozen=True)
class Proposal:
    """A paired proposal: the message to execute and what the operator is shown."""

    request_id: int
    message: Any  # nav_msgs/Path or trajectory_msgs/JointTrajectory; opaque here
    outcome: PlanningOutcome
    work_s: float  # nominal execution time on the robot clock (s)


_Key = TypeVar("_Key", bound=Hashable)
_Value = TypeVar("_Value")
_PairKey = tuple[PlannerKind, int]  # (kind, stamp in ns): how a message and its outcome are paired


class _Bounded(OrderedDict[_Key, _Value]):
    """An OrderedDict that forgets its oldest entries beyond ``capacity``."""

    def __init__(self, capacity: int) -> None:
        super().__init__()
        self.capacity = capacity

    def __setitem__(self, key: _Key, value: _Value) -> None:
        super().__setitem__(key, value)
        while len(self) > self.capacity:
            self.popitem(last=False)


class PlanExchange:
    def __init__(self, work_of: Callable[[Any], float], capacity: int = 16) -> None:
        """``work_of(message)``: the nominal execution time of a proposal message (s)."""
        self._work_of = work_of
        self.current = 0  # the request id the machine waits on
        self._messages: _Bounded[_PairKey, Any] = _Bounded(capacity)  # message without its outcome yet
        self._outcomes: _Bounded[_PairKey, PlanningOutcome] = _Bounded(capacity)  # outcome without its message yet
        self._ready: _Bounded[int, Proposal] = _Bounded(capacity)  # request id → Proposal, until executed
        self._executing: _Bounded[int, int] = _Bounded(capacity)  # sent stamp (ns) → request id

    def begin(self, request_id: int) -> None:
        """A new request is out: answers to older ones are stale from now on."""
        self.current = request_id
        for rid in [rid for rid in self._ready if rid != request_id]:
            del self._ready[rid]
        for key in [k for k, o in self._outcomes.items() if o.request_id != request_id]:
            del self._outcomes[key]

    def add_message(self, kind: PlannerKind, stamp_ns: int, message: Any) -> Proposal | None:
        """A proposal message arrived; returns the pair when its outcome is already here."""
        outcome = self._outcomes.pop((kind, stamp_ns), None)
        if outcome is None:
            self._messages[(kind, stamp_ns)] = message
            return None
        return self._pair(outcome, message)

    def add_outcome(self, kind: PlannerKind, outcome: PlanningOutcome) -> Proposal | PlanningOutcome | None:
        """A planning outcome arrived. Returns None when it is stale or waits for its message,
        the outcome itself when it is a failure of the current request, else the pair."""
        if outcome.request_id != self.current:
            return None
        if outcome.status is not OutcomeStatus.SUCCESS:
            return outcome
        key = (kind, outcome.stamp_ns)
        message = self._messages.pop(key, None)
        if message is None:
            self._outcomes[key] = outcome
            return None
        return self._pair(outcome, message)

    def _pair(self, outcome: PlanningOutcome, message: Any) -> Proposal:
        proposal = Proposal(outcome.request_id, message, outcome, float(self._work_of(message)))
        self._ready[outcome.request_id] = proposal
        return proposal

    def take(self, request_id: int) -> Proposal | None:
        """The proposal of ``request_id``, once; None if there is none (or it was taken)."""
        return self._ready.pop(request_id, None)

    def sent(self, stamp_ns: int, request_id: int) -> None:
        """The proposal of ``request_id`` went to the robot stamped ``stamp_ns``."""
        self._executing[stamp_ns] = request_id

    def finished(self, stamp_ns: int) -> int | None:
        """The request whose execution stamped ``stamp_ns`` ended (None: not ours, or reported)."""
        return self._executing.pop(stamp_ns, None)

    def sizes(self) -> dict[str, int]:
        """How many entries each table holds (diagnostics; they stay bounded)."""
        return {"messages": len(self._messages), "outcomes": len(self._outcomes),
                "ready": len(self._ready), "executing": len(self._executing)}
