"""What the operator is asked, and why an answer does not apply: pure functions of the machine's
state (:mod:`door_fsm.machine`)."""

from __future__ import annotations

from door_contract.payloads import ProposalSummary
from door_fsm.operator_commands import OperatorCommand, OperatorWord
from door_fsm.states import Phase
from door_fsm.work import StateWork

__all__ = ["approval_text", "refusal"]


def approval_text(state_label: str, request_id: int, work: StateWork, summary: ProposalSummary) -> str:
    """``WALK_TO_DOOR #7: approve footsteps 'stand'? steps=14 | reply 'approve 7', …``."""
    figures = ", ".join(f"{k}={v}" for k, v in summary.items())
    return (f"{state_label} #{request_id}: approve {work.kind.value} '{work.subject}'? {figures} "
            f"| reply 'approve {request_id}', 'reject {request_id}' or 'repeat {request_id}'; "
            f"pause, stop, abort, manual")


def refusal(word: OperatorWord, state_label: str, work: StateWork | None, request_id: int,
            phase: Phase | None) -> str:
    """Why an answer (approve/reject/repeat N) does not apply now; '' when it does. It must name
    the current request, and ``approve`` only while that request awaits approval."""
    if work is None or phase is None:
        return f"'{word}' refused: nothing is proposed in {state_label}"
    if word.request_id != request_id:
        return f"'{word}' refused: the current request is #{request_id} ({state_label}, {phase.value}); nothing changed"
    if word.command is OperatorCommand.APPROVE and phase is not Phase.AWAITING_APPROVAL:
        return f"'{word}' refused: request #{request_id} is {phase.value}, not awaiting approval"
    return ""
