"""Operator commands on ``/door_task/operator`` (a std_msgs/String, as ``ros2 topic pub`` sends)."""

from __future__ import annotations

from enum import Enum


class OperatorCommand(str, Enum):
    APPROVE = "approve"
    REJECT = "reject"
    REPEAT = "repeat"
    PAUSE = "pause"
    RESUME = "resume"
    ABORT = "abort"
    MANUAL = "manual"


class UnknownCommandError(ValueError):
    pass


def parse_command(text: str) -> OperatorCommand:
    """The command in ``text`` (case and surrounding spaces ignored) or UnknownCommandError."""
    try:
        return OperatorCommand(text.strip().lower())
    except ValueError:
        allowed = ", ".join(c.value for c in OperatorCommand)
        raise UnknownCommandError(f"unknown operator command {text!r}; use one of {allowed}") from None


class AutonomyLevel(str, Enum):
    """Which proposals wait for the operator (as FlexBE's autonomy levels)."""

    FULL = "full"              # none
    SUPERVISED = "supervised"  # the critical ones (door estimate, footstep plans, handle turn)
    STEP = "step"              # every proposal
