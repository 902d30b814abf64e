"""Tables in the form of [Banerjee 2015]'s Table I: per phase, success, planning time, moving time."""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

from door_contract.payloads import StateAttempt, decode_document
from door_contract.vocabulary import AttemptOutcome, TaskState

__all__ = ["PHASES", "PhaseRow", "format_table", "phase_of", "phase_rows", "state_attempts"]

PHASES = ("DETECT_DOOR", "WALK_TO_DOOR", "OPEN_DOOR", "WALK_THROUGH")


@dataclass(frozen=True)
class PhaseRow:
    phase: str
    runs: int
    successes: int
    planning_s: float  # mean per run
    moving_s: float  # mean per run
    waiting_s: float  # mean per run (operator)
    falls: int = 0  # runs in which the robot fell in this phase
    slips: int = 0  # attempts of this phase that ended with the hand slipping off the handle

    @property
    def success_rate(self) -> float:
        return self.successes / self.runs if self.runs else 0.0


@dataclass
class _PhaseTally:
    """One phase's sums over the runs (:func:`phase_rows`)."""

    runs: int = 0
    successes: int = 0
    falls: int = 0
    slips: int = 0
    planning_s: float = 0.0
    moving_s: float = 0.0
    waiting_s: float = 0.0

    def add_run(self, attempts: list[StateAttempt]) -> None:
        """One run's attempts at this phase: it succeeded when its last attempt did."""
        self.runs += 1
        self.successes += int(attempts[-1].outcome is AttemptOutcome.SUCCEEDED)
        self.falls += int(any(attempt.outcome is AttemptOutcome.FELL for attempt in attempts))
        self.slips += sum(int(attempt.outcome is AttemptOutcome.SLIPPED) for attempt in attempts)
        self.planning_s += sum(attempt.planning_s for attempt in attempts)
        self.moving_s += sum(attempt.moving_s for attempt in attempts)
        self.waiting_s += sum(attempt.waiting_s for attempt in attempts)

    def row(self, phase: str) -> PhaseRow:
        runs = max(self.runs, 1)
        return PhaseRow(phase, self.runs, self.successes, self.planning_s / runs, self.moving_s / runs,
                        self.waiting_s / runs, self.falls, self.slips)


def phase_of(state: TaskState) -> str:
    """The Table I phase of a state: TURN_HANDLE's is OPEN_DOOR, TUCK's WALK_THROUGH (a
    sub-state's label, ``OPEN_DOOR/TURN_HANDLE``, names its phase first), any other state's its
    own name (PAUSED is no phase of the table)."""
    return state.label.split("/", 1)[0]


def state_attempts(report: Mapping[str, Any]) -> list[StateAttempt]:
    """The state attempts of a run's report (a dict: the main job's, or one read back from
    ``report.json`` / ``trial.json``), each as the FSM reported it (a ContractError names a
    malformed one)."""
    return [attempt if isinstance(attempt, StateAttempt) else decode_document(StateAttempt, attempt)
            for attempt in report["attempts"]]


def phase_rows(reports: Iterable[Mapping[str, Any]]) -> list[PhaseRow]:
    """Rows over one or many TaskReports (dicts): a phase succeeds in a run when its last
    attempt succeeded and the run went on past it; its falls and slips are counted too."""
    tallies = {phase: _PhaseTally() for phase in PHASES}
    for report in reports:
        by_phase: dict[str, list[StateAttempt]] = defaultdict(list)
        for attempt in state_attempts(report):
            by_phase[phase_of(attempt.state)].append(attempt)
        for phase, attempts in by_phase.items():
            if phase in tallies:
                tallies[phase].add_run(attempts)
    return [tallies[phase].row(phase) for phase in PHASES]


CLOCKS = "planning and operator time: wall clock; moving time: the robot's clock (sim time) — docs/CLOCKS.md"


def format_table(rows: list[PhaseRow], overall_runs: int, overall_successes: int, title: str) -> str:
    """Markdown table: phase | success | falls | slips | planning time | moving time | operator
    time, and the clock each column is measured on."""
    lines = [f"### {title}", "", f"({CLOCKS})", "",
             "| phase | success | falls | slips | planning time (wall) | moving time (robot) | operator time (wall) |",
             "|---|---|---|---|---|---|---|"]
    for row in rows:
        lines.append(f"| {row.phase} | {row.successes}/{row.runs} ({100 * row.success_rate:.0f} %) | {row.falls} | "
                     f"{row.slips} | {row.planning_s:.3f} s | {row.moving_s:.1f} s | {row.waiting_s:.1f} s |")
    rate = 100.0 * overall_successes / overall_runs if overall_runs else 0.0
    lines.append(f"| **overall** | **{overall_successes}/{overall_runs} ({rate:.0f} %)** | "
                 f"{sum(r.falls for r in rows)} | {sum(r.slips for r in rows)} | "
                 f"{sum(r.planning_s for r in rows):.3f} s | {sum(r.moving_s for r in rows):.1f} s | "
                 f"{sum(r.waiting_s for r in rows):.1f} s |")
    return "\n".join(lines)
