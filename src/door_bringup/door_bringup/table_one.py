"""Tables in the form of [Banerjee 2015]'s Table I: per phase, success, planning time, moving time."""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

from door_contract.payloads import StateAttempt, decode_document
from door_contract.vocabulary import AttemptOutcome, TaskState

PHASES = ("DETECT_DOOR", "WALK_TO_DOOR", "OPEN_DOOR", "WALK_THROUGH")


@dataclass(frozen=True)
class PhaseRow:
    phase: str
    runs: int
    successes: int
    planning_s: float  # mean per run
    moving_s: float  # mean per run
    waiting_s: float  # mean per run (operator)

    @property
    def success_rate(self) -> float:
        return self.successes / self.runs if self.runs else 0.0


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
    attempt succeeded and the run went on past it."""
    totals: dict[str, list[float]] = defaultdict(lambda: [0, 0, 0.0, 0.0, 0.0])
    for report in reports:
        seen: dict[str, dict] = {}
        for attempt in state_attempts(report):
            phase = phase_of(attempt.state)
            entry = seen.setdefault(phase, {"ok": True, "plan": 0.0, "move": 0.0, "wait": 0.0})
            entry["plan"] += attempt.planning_s
            entry["move"] += attempt.moving_s
            entry["wait"] += attempt.waiting_s
            entry["last"] = attempt.outcome
        for phase, entry in seen.items():
            row = totals[phase]
            row[0] += 1
            row[1] += 1 if entry["last"] is AttemptOutcome.SUCCEEDED else 0
            row[2] += entry["plan"]
            row[3] += entry["move"]
            row[4] += entry["wait"]
    rows = []
    for phase in PHASES:
        runs, ok, plan, move, wait = totals.get(phase, [0, 0, 0.0, 0.0, 0.0])
        rows.append(PhaseRow(phase, int(runs), int(ok), plan / runs if runs else 0.0,
                             move / runs if runs else 0.0, wait / runs if runs else 0.0))
    return rows


CLOCKS = "planning and operator time: wall clock; moving time: the robot's clock (sim time) — docs/CLOCKS.md"


def format_table(rows: list[PhaseRow], overall_runs: int, overall_successes: int, title: str) -> str:
    """Markdown table: phase | success | planning time | moving time | operator time, and the
    clock each column is measured on."""
    lines = [f"### {title}", "", f"({CLOCKS})", "",
             "| phase | success | planning time (wall) | moving time (robot) | operator time (wall) |",
             "|---|---|---|---|---|"]
    for row in rows:
        lines.append(f"| {row.phase} | {row.successes}/{row.runs} ({100 * row.success_rate:.0f} %) | "
                     f"{row.planning_s:.3f} s | {row.moving_s:.1f} s | {row.waiting_s:.1f} s |")
    rate = 100.0 * overall_successes / overall_runs if overall_runs else 0.0
    lines.append(f"| **overall** | **{overall_successes}/{overall_runs} ({rate:.0f} %)** | "
                 f"{sum(r.planning_s for r in rows):.3f} s | {sum(r.moving_s for r in rows):.1f} s | "
                 f"{sum(r.waiting_s for r in rows):.1f} s |")
    return "\n".join(lines)
