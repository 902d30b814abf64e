"""Operator commands on ``/door_task/operator`` (a std_msgs/String, as ``ros2 topic pub`` sends).

An answer names the request it answers: ``approve 7``, ``reject 7``, ``repeat 7`` — the id is
in the approval request (``WALK_TO_DOOR #7: …``), so a late or repeated approval can never
apply to a newer proposal the operator has not seen (issue #12: of 100 ``approve`` in one
second, the second approved a footstep plan 64 ms after it was proposed). ``pause``,
``stop``, ``resume``, ``abort`` and ``manual`` need no id: stopping must never wait for one.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from enum import Enum

from door_fsm.errors import DoorFsmError

__all__ = ["MAX_COMMAND_CHARS", "OperatorCommand", "OperatorWord", "UnknownCommandError", "parse_command",
           "request_id_of", "usage"]

MAX_COMMAND_CHARS = 200
_REQUEST_ID = re.compile(r"#(\d+)\b")


class OperatorCommand(str, Enum):
    APPROVE = "approve"
    REJECT = "reject"
    REPEAT = "repeat"
    PAUSE = "pause"
    STOP = "stop"
    RESUME = "resume"
    ABORT = "abort"
    MANUAL = "manual"

    @property
    def answers_a_request(self) -> bool:
        """approve, reject and repeat answer one request and must name its id."""
        return self in (OperatorCommand.APPROVE, OperatorCommand.REJECT, OperatorCommand.REPEAT)


@dataclass(frozen=True)
class OperatorWord:
    """One parsed command; ``request_id`` is set exactly for the answers."""

    command: OperatorCommand
    request_id: int | None = None

    def __str__(self) -> str:
        return self.command.value if self.request_id is None else f"{self.command.value} {self.request_id}"


class UnknownCommandError(DoorFsmError):
    """Text on /door_task/operator that is no command; the message says what is accepted."""


def parse_command(text: str) -> OperatorWord:
    """The command in ``text`` (case and spaces ignored), or :class:`UnknownCommandError`."""
    shown = text if len(text) <= 60 else text[:60] + "…"
    if len(text) > MAX_COMMAND_CHARS:
        raise UnknownCommandError(f"operator command of {len(text)} characters refused")
    words = text.strip().lower().split()
    command = next((c for c in OperatorCommand if words and c.value == words[0]), None)
    if command is None:
        raise UnknownCommandError(f"unknown operator command {shown!r}; use {usage()}")
    if not command.answers_a_request:
        if len(words) > 1:
            raise UnknownCommandError(f"'{command.value}' takes no request id (got {shown!r})")
        return OperatorWord(command)
    if len(words) != 2 or not words[1].isdigit():
        raise UnknownCommandError(f"'{command.value}' needs the id of the request it answers, e.g. "
                                  f"'{command.value} 7' (the id follows '#' in the approval request); got {shown!r}")
    return OperatorWord(command, int(words[1]))


def request_id_of(approval_request: str) -> int | None:
    """The id an approval request shows (``WALK_TO_DOOR #7: approve …`` → 7), or None."""
    match = _REQUEST_ID.search(approval_request)
    return int(match.group(1)) if match else None


def usage() -> str:
    return "approve N, reject N, repeat N (N = the request id), pause, stop, resume, abort or manual"

