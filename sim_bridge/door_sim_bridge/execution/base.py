"""What the executions share: the outcome, the phases, and stepping an execution incrementally.

An execution validates its input on construction; invalid input ends it at once as REJECTED
and it never touches the world. A valid one moves the robot only from :meth:`command`, which
sets the commands for the world's current time and returns whether it has finished, so a
ROS node can interleave publishing with physics steps::

    execution = TrajectoryExecution(world, times, names, positions)
    while not execution.command():
        world.step()          # … publish /joint_states, /clock between steps
    outcome = execution.result
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass
from enum import Enum

from door_contract.payloads import ExecutionKind, ExecutionOutcome, OutcomeStatus
from door_sim_bridge.world.world import DoorWorld, EventKind, SimEvent

__all__ = ["Execution", "ExecutionPhase", "ExecutionResult"]


@dataclass(frozen=True)
class ExecutionResult:
    """How an execution ended: status, the reason of a rejection or failure, simulated duration."""

    status: OutcomeStatus
    reason: str = ""
    duration_s: float = 0.0
    slipped: bool = False  # ended because a hand slipped off the handle

    def outcome(self, kind: ExecutionKind, request_id: int) -> ExecutionOutcome:
        """The contract's payload for ``/sim/execution_outcome``."""
        return ExecutionOutcome(kind, request_id, self.status, self.reason, self.duration_s, self.slipped)


class ExecutionPhase(str, Enum):
    PENDING = "pending"  # valid, not started (starts at the first command())
    RUNNING = "running"
    SETTLING = "settling"  # holding the final command before judging
    FINISHED = "finished"


class Execution(ABC):
    """Incremental execution on a :class:`DoorWorld` (base class)."""

    def __init__(self, world: DoorWorld) -> None:
        self.world = world
        self.phase = ExecutionPhase.PENDING
        self.result: ExecutionResult | None = None
        self._start_time = 0.0
        self._event_cursor = 0
        self.stop_reason: str | None = None  # set by stop(); the execution ends as soon as it safely can
        if world.fallen:  # whatever it asks, nothing executes on a fallen robot
            self._fell()

    @property
    def done(self) -> bool:
        return self.phase is ExecutionPhase.FINISHED

    @property
    def elapsed(self) -> float:
        """Simulated seconds since the first command (0 before)."""
        return 0.0 if self.phase is ExecutionPhase.PENDING else self.world.time - self._start_time

    def command(self) -> bool:
        """Set the robot's commands for the world's current time; True once finished."""
        if self.done:
            return True
        if self.world.fallen:
            self._fell()
            return True
        if self.phase is ExecutionPhase.PENDING:
            self._start_time = self.world.time
            self._event_cursor = len(self.world.events())
            self.phase = ExecutionPhase.RUNNING
            self._on_start()
        self._command_now()
        return self.done

    def advance(self, steps: int = 1) -> bool:
        """Command and step the world up to ``steps`` times; True once finished (no step then)."""
        for _ in range(steps):
            if self.command():
                return True
            self.world.step()
        return self.command()

    def run(self, max_steps: int = 10**7) -> ExecutionResult:
        """Advance until finished (or ``max_steps``, then cancel) and return the result."""
        if not self.advance(max_steps):
            self.cancel(f"did not finish within {max_steps} physics steps")
        assert self.result is not None
        return self.result

    def stop(self, reason: str) -> None:
        """Stop on command (an empty message, a lost supervisor): the execution finishes with
        STOPPED and ``reason`` — at once if it never started, else where the subclass says
        the robot is safe to leave: :meth:`_on_stop` (trajectory: hold the current positions
        now; footsteps: at the next stable stance). A no-op once finished."""
        if self.done:
            return
        if self.phase is ExecutionPhase.PENDING:
            self._finish(OutcomeStatus.STOPPED, reason)
            return
        self.stop_reason = reason
        self._on_stop()

    def cancel(self, reason: str = "cancelled") -> ExecutionResult:
        """Stop where the robot is and finish with FAILURE (no-op once finished)."""
        if not self.done:
            self._hold()
            self._finish(OutcomeStatus.FAILURE, reason)
        assert self.result is not None
        return self.result

    # ------------------------------------------------------------------ for subclasses
    def _reject(self, reason: str) -> None:
        if self.done:  # already ended (the robot had fallen)
            return
        self.phase = ExecutionPhase.FINISHED
        self.result = ExecutionResult(OutcomeStatus.REJECTED, reason, 0.0)

    def _finish(self, status: OutcomeStatus, reason: str = "", slipped: bool = False) -> None:
        self.result = ExecutionResult(status, reason, self.elapsed, slipped)
        self.phase = ExecutionPhase.FINISHED

    def _fell(self) -> None:
        """The robot is down: end with FELL (a plan sent after the fall moves nothing)."""
        elapsed = self.elapsed
        self.phase = ExecutionPhase.FINISHED
        self.result = ExecutionResult(OutcomeStatus.FELL, str(self.world.fall_reason), elapsed)  # the status says it fell

    def _slip_since_start(self) -> SimEvent | None:
        """The first grasp slip recorded since this execution started, if any."""
        events = self.world.events_since(self._event_cursor)
        return next((event for event in events if event.kind is EventKind.GRASP_SLIPPED), None)

    def _on_start(self) -> None:  # noqa: B027  (an optional hook: most executions need no start action)
        """Hook called at the first command."""

    def _on_stop(self) -> None:
        """Hook of :meth:`stop` for a running execution; by default: hold now and finish."""
        self._hold()
        self._finish(OutcomeStatus.STOPPED, f"stopped: {self.stop_reason}")

    @abstractmethod
    def _command_now(self) -> None:
        """Set commands for ``world.time``; call :meth:`_finish` when done."""

    @abstractmethod
    def _hold(self) -> None:
        """Freeze the robot where it is (used by :meth:`cancel`)."""
