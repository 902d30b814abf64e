"""The FSM's two clocks and its per-attempt records (Table I), ROS-free.

Each phase's deadline and time runs on the clock of what it waits for (docs/CLOCKS.md):
planning and the operator's answer on the **wall** clock (planners compute and people read
in real time, whatever the simulation's speed), execution on the **robot** clock (sim time
under ``use_sim_time``: a 40-step walk takes 40 step times of the robot's time, however
fast the simulation runs on this machine). The detector answers at the robot's pace (camera
frames, head moves): DETECT_DOOR's planning deadline is on the robot clock, its time still
counted on the wall clock with the other planning (the overhead a run waits for).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum

from door_contract.payloads import ProposalSummary, StateAttempt
from door_contract.vocabulary import AttemptOutcome, TaskState
from door_fsm.states import Phase, StateOutcome

__all__ = ["PHASE_CLOCK", "Clock", "Deadline", "Instant", "StateRecord", "clocks_note"]


class Clock(str, Enum):
    WALL = "wall"    # steady (monotonic) seconds
    ROBOT = "robot"  # the robot's time: /clock under use_sim_time, else the system clock


PHASE_CLOCK = {Phase.PLANNING: Clock.WALL, Phase.AWAITING_APPROVAL: Clock.WALL, Phase.EXECUTING: Clock.ROBOT}


@dataclass(frozen=True)
class Deadline:
    """When a phase runs out: ``at`` s on ``clock``, ``limit_s`` after the phase began."""

    clock: Clock
    at: float
    limit_s: float

    @classmethod
    def after(cls, now: Instant, clock: Clock, limit_s: float) -> Deadline:
        return cls(clock, now.on(clock) + limit_s, limit_s)

    def passed(self, now: Instant) -> bool:
        return now.on(self.clock) > self.at

    def __str__(self) -> str:
        return f"{self.limit_s:.1f} s ({self.clock.value} clock)"


@dataclass(frozen=True)
class Instant:
    """One moment read on both clocks (s)."""

    wall: float
    robot: float

    def on(self, clock: Clock) -> float:
        return self.wall if clock is Clock.WALL else self.robot

    def later(self, seconds: float) -> Instant:
        """Both clocks advanced by ``seconds`` (for tests and simulations of the machine)."""
        return Instant(self.wall + seconds, self.robot + seconds)


@dataclass
class StateRecord:
    """One attempt at one state, for the Table I report (times in seconds, see PHASE_CLOCK)."""

    state: TaskState
    attempt: int  # 1 for the first try (the request's ``attempt`` is this − 1)
    started: Instant
    outcome: StateOutcome | None = None
    planning_s: float = 0.0  # wall clock
    waiting_s: float = 0.0   # wall clock
    moving_s: float = 0.0    # robot clock
    reason: str = ""
    summary: ProposalSummary = field(default_factory=dict)
    robot_s: float = 0.0     # robot clock, entry to outcome (set by :meth:`conclude`)

    def add(self, phase: Phase, seconds: float) -> None:
        if phase is Phase.PLANNING:
            self.planning_s += seconds
        elif phase is Phase.AWAITING_APPROVAL:
            self.waiting_s += seconds
        else:
            self.moving_s += seconds

    def conclude(self, outcome: StateOutcome, reason: str, now: Instant) -> None:
        """The attempt's outcome, and its length on the robot clock: for DETECT_DOOR the
        detection latency in sim time, whatever the machine's load (issue #15's ≤ 0.5 s)."""
        self.outcome, self.reason = outcome, reason
        self.robot_s = max(0.0, now.robot - self.started.robot)

    def as_state_attempt(self) -> StateAttempt:
        """This attempt as the TaskReport lists it (times rounded to 0.1 ms; unfinished while
        the state has no outcome)."""
        outcome = AttemptOutcome(self.outcome.value) if self.outcome else AttemptOutcome.UNFINISHED
        return StateAttempt(self.state, self.attempt, outcome, round(self.planning_s, 4),
                            round(self.waiting_s, 4), round(self.moving_s, 4), self.reason, dict(self.summary),
                            round(self.robot_s, 4))


def clocks_note(robot_clock: str) -> str:
    """What the TaskReport's times are measured on; ``robot_clock`` is "sim" or "wall"."""
    return (f"planning_s, waiting_s: wall clock (steady); moving_s, robot_s: robot clock "
            f"({robot_clock} time)")
