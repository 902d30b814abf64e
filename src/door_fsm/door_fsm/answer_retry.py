"""An automatic operator's answer, sent again until the FSM has taken it.

The approval request is latched, the operator's answers are not (``/door_task/operator`` keeps
only what live subscribers receive). An operator that joins while a request is out receives the
latched request at once and answers it, sometimes before DDS has matched its publisher with the
FSM's subscription: the answer is lost, and the FSM waits its 300 s approval timeout (a fresh
clone's main job ended FAILED in DETECT_DOOR exactly so, stop 38). So an answer is repeated
every ``resend_after_s`` while the same request is still the one out; the FSM clears the request
(an empty message) when it takes an answer, and refuses a duplicate that arrives after that with
a log line and nothing changed (:func:`door_fsm.approvals.refusal`).

Pure: times are passed in (seconds of a monotonic clock); the node owns the clock and the
publisher.
"""

from __future__ import annotations

from dataclasses import dataclass

from door_fsm.operator_commands import request_id_of

__all__ = ["AnswerRetry", "RetryOptions"]


@dataclass(frozen=True)
class RetryOptions:
    resend_after_s: float = 2.0
    """s (wall clock) without the request being cleared after which the answer is sent again;
    well above DDS delivery on a loaded machine (~10 ms), well below the FSM's approval
    timeout (300 s)."""
    check_period_s: float = 0.5
    """s between a node's calls of :meth:`AnswerRetry.due` (its timer): a repeat goes out at most
    this late."""

    def __post_init__(self) -> None:
        for name in ("resend_after_s", "check_period_s"):
            if not getattr(self, name) > 0.0:
                raise ValueError(f"{name} must be > 0 s, got {getattr(self, name)}")


class AnswerRetry:
    """Which request id to approve now: the current request's when it is new, and again each
    ``resend_after_s`` until the FSM clears or replaces it."""

    def __init__(self, options: RetryOptions | None = None) -> None:
        self.options = options or RetryOptions()
        self.pending: int | None = None  # the id of the request out and answered, not yet taken
        self.sent_at = 0.0
        self.sends = 0  # answers sent, repeats included

    def on_request(self, text: str, now: float) -> int | None:
        """The latched request changed to ``text`` ('' clears it); the id to answer at once, if any."""
        request_id = request_id_of(text) if text else None
        if request_id == self.pending:
            return None  # the same request again (a late joiner's copy): its answer is on its way
        self.pending = request_id
        return self._sent(now) if request_id is not None else None

    def due(self, now: float) -> int | None:
        """The id to answer again at ``now``: the request is still out ``resend_after_s`` after
        the last answer."""
        if self.pending is None or now - self.sent_at < self.options.resend_after_s:
            return None
        return self._sent(now)

    def _sent(self, now: float) -> int | None:
        self.sent_at, self.sends = now, self.sends + 1
        return self.pending
