"""Actions the machine asks the supervisor node to perform (publish, call, execute)."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class RequestDetection:
    request_id: int


@dataclass(frozen=True)
class RequestFootsteps:
    request_id: int
    goal: str  # "stand" | "through"


@dataclass(frozen=True)
class RequestMotion:
    request_id: int
    motion: str


@dataclass(frozen=True)
class CallGrasp:
    request_id: int
    close: bool


@dataclass(frozen=True)
class Execute:
    """Send the approved proposal of ``request_id`` to the robot."""

    request_id: int
    kind: str  # "footsteps" | "motion"


@dataclass(frozen=True)
class AskApproval:
    text: str


@dataclass(frozen=True)
class ClearApproval:
    pass


@dataclass(frozen=True)
class AnnounceState:
    state: str
    reason: str = ""


@dataclass(frozen=True)
class Notice:
    """Something the operator should read in the log (e.g. an ignored command)."""

    text: str


Action = (RequestDetection | RequestFootsteps | RequestMotion | CallGrasp | Execute | AskApproval
          | ClearApproval | AnnounceState | Notice)
