"""How a planner node serves requests: one answer per request id, planning off the executor.

Issue #12 found the planners answering 23 (footsteps) and 7 (optimiser) of 100 requests sent
in one second, the rest dropped without a line; a request with a readable id but a missing
field got no outcome; and while one plan ran (80 s for a hostile door angle) nothing else
was served, heartbeats included. The rules here, ROS-free:

* :func:`decode_request` reads the id even from an invalid request, so the node can answer
  it REJECTED with the reason; only text without a readable id goes unanswered (logged).
* :class:`PlanningWorker` runs one job at a time on its own thread, so the node's executor
  keeps serving heartbeats, cancels and new requests. The newest request wins: a queued
  older one is answered SUPERSEDED at once, a running one when it ends (its result is then
  never proposed); :meth:`PlanningWorker.cancel` does the same for an explicit cancel. So
  a burst is never dropped: every request ends in exactly one :class:`Finished`.

Results come back through :meth:`PlanningWorker.take_finished` on the node's own thread
(``wake`` is called from the worker, e.g. an rclpy guard condition's ``trigger``), so every
publication happens on the executor thread.
"""

from __future__ import annotations

import threading
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass
from enum import Enum
from typing import Any, TypeVar

from door_contract.errors import ContractError
from door_contract.json_text import read_request_id
from door_contract.payloads import OutcomeStatus, decode

__all__ = ["CancelResult", "Finished", "PlanningWorker", "decode_request", "request_id_of"]

Request = TypeVar("Request")


def decode_request(payload_type: type[Request], text: str) -> tuple[Request | None, int | None, str]:
    """``(request, id, "")`` for a valid request; ``(None, id, reason)`` for an invalid one
    whose id can be read (answer it REJECTED); ``(None, None, reason)`` when even the id
    cannot be read."""
    try:
        request = decode(payload_type, text)
    except ContractError as error:
        return None, read_request_id(text), str(error)
    return request, getattr(request, "request_id", None), ""


@dataclass(frozen=True)
class Finished:
    """How one request ended: the job's ``result`` or ``error``, or why it was dropped."""

    request: Any
    result: Any = None
    error: BaseException | None = None
    dropped: str = ""  # non-empty: superseded or cancelled; answer SUPERSEDED, propose nothing

    def answer_without_result(self, refusals: tuple[type[BaseException], ...]) -> tuple[OutcomeStatus, str] | None:
        """How a request that has no result to propose is answered, or None when it has one.

        SUPERSEDED when it was dropped; REJECTED with the error's text when the job refused
        its input with one of ``refusals`` (the node's bad-input errors: never a bare
        ``ValueError``, which a bug raises too); FAILURE ``"internal error: …"`` for any
        other exception: a bug ends the request, not the node."""
        if self.dropped:
            return OutcomeStatus.SUPERSEDED, self.dropped
        if self.error is None:
            return None
        if isinstance(self.error, refusals):
            return OutcomeStatus.REJECTED, str(self.error)
        return OutcomeStatus.FAILURE, f"internal error: {self.error!r}"


class CancelResult(str, Enum):
    QUEUED = "queued"    # removed before it started: answered now
    RUNNING = "running"  # answered when its job returns; the result is discarded
    UNKNOWN = "unknown"  # not queued or running (already answered, or never seen)


class PlanningWorker:
    def __init__(self, wake: Callable[[], None], name: str = "planning") -> None:
        self._wake = wake
        self._lock = threading.Condition()
        self._queued: tuple[Any, Callable[[], Any]] | None = None
        self._running: Any = None
        self._running_dropped = ""
        self._finished: deque[Finished] = deque()
        self._closing = False
        self._thread = threading.Thread(target=self._loop, name=name, daemon=True)
        self._thread.start()

    def submit(self, request: Any, job: Callable[[], Any]) -> None:
        """Queue ``job`` for ``request``; whatever was queued or running before is superseded."""
        with self._lock:
            why = f"superseded by request {request_id_of(request)}"
            if self._queued is not None:
                self._finished.append(Finished(self._queued[0], dropped=why))
            if self._running is not None and not self._running_dropped:
                self._running_dropped = why
            self._queued = (request, job)
            self._lock.notify()
        self._wake()

    def cancel(self, request_id: int, reason: str) -> CancelResult:
        with self._lock:
            why = f"cancelled: {reason}" if reason else "cancelled"
            if self._queued is not None and request_id_of(self._queued[0]) == request_id:
                self._finished.append(Finished(self._queued[0], dropped=why))
                self._queued = None
                result = CancelResult.QUEUED
            elif self._running is not None and request_id_of(self._running) == request_id:
                self._running_dropped = self._running_dropped or why
                return CancelResult.RUNNING
            else:
                return CancelResult.UNKNOWN
        self._wake()
        return result

    def take_finished(self) -> list[Finished]:
        """Every request that ended since the last call (call on the node's thread)."""
        with self._lock:
            finished, self._finished = list(self._finished), deque()
        return finished

    @property
    def busy(self) -> bool:
        with self._lock:
            return self._running is not None or self._queued is not None

    def close(self, timeout_s: float = 1.0) -> None:
        """Stop taking jobs; a running one is left to finish on its daemon thread."""
        with self._lock:
            self._closing = True
            self._lock.notify()
        self._thread.join(timeout_s)

    def _loop(self) -> None:
        while True:
            with self._lock:
                while self._queued is None and not self._closing:
                    self._lock.wait()
                if self._closing:
                    return
                if self._queued is None:  # not reached: the wait above ends with a job or on closing
                    continue
                (request, job), self._queued = self._queued, None
                self._running, self._running_dropped = request, ""
            finished = self._run(request, job)
            with self._lock:
                if self._running_dropped:
                    finished = Finished(request, dropped=self._running_dropped)
                self._running = None
                self._finished.append(finished)
            self._wake_safely()

    @staticmethod
    def _run(request: Any, job: Callable[[], Any]) -> Finished:
        try:
            return Finished(request, result=job())
        except Exception as error:  # reported as this request's outcome by the node
            return Finished(request, error=error)

    def _wake_safely(self) -> None:
        try:
            self._wake()
        except Exception:  # the node is being destroyed; nothing is left to answer to
            pass


def request_id_of(request: Any) -> int | None:
    return getattr(request, "request_id", None)
