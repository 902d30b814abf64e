"""What the operator sees in an approval request: short summaries of proposals."""

from __future__ import annotations

import numpy as np

from door_contract.payloads import (
    DoorEstimate,
    FootstepFigures,
    MotionFigures,
    PlanningOutcome,
    ProposalSummary,
    StateAttempt,
    TaskReport,
)
from door_contract.vocabulary import Autonomy, DoorOpening, TaskEnd

__all__ = ["door_summary", "footstep_summary", "motion_summary", "plan_summary", "task_report", "work_of"]


def door_summary(estimate: DoorEstimate) -> ProposalSummary:
    """What the operator is shown of a door estimate: the grasp point, width, hinge, confidence."""
    handle = np.asarray(estimate.handle_position)
    return {"handle_m": "(" + ", ".join(f"{v:.2f}" for v in handle) + ")",
            "width_m": round(estimate.width, 3), "hinge": estimate.hinge_side.value,
            "confidence": round(estimate.confidence, 2), "mode": estimate.mode}


def plan_summary(outcome: PlanningOutcome) -> ProposalSummary:
    """What the operator is shown of a plan: the planner's figures (no trajectories) and the
    planning time (ms)."""
    summary: ProposalSummary = {}
    if outcome.footsteps is not None:
        summary.update(footstep_summary(outcome.footsteps))
    if outcome.motion is not None:
        summary.update(motion_summary(outcome.motion))
    summary["planning_ms"] = round(outcome.planning_time_s * 1000.0, 1)
    return summary


def footstep_summary(figures: FootstepFigures) -> ProposalSummary:
    """A footstep plan's steps and walked length (m)."""
    return {"steps": figures.steps, "length_m": figures.length_m}


def motion_summary(figures: MotionFigures) -> ProposalSummary:
    """A motion plan's duration (s), cost, largest violation, iterations and backend; a figure
    that is not finite (None) is not shown."""
    shown: dict[str, str | float | int | None] = {
        "duration_s": figures.duration_s, "cost": figures.cost, "max_violation": figures.max_violation,
        "iterations": figures.iterations, "backend": figures.backend}
    return {name: value for name, value in shown.items() if value is not None}


def work_of(message: object, step_duration: float) -> float:
    """Nominal execution time of a proposal (robot clock, s): a trajectory's duration, or a
    footstep plan's steps × the robot profile's step duration."""
    points = getattr(message, "points", None)
    if points is not None:
        if not points:
            return 0.0
        last = points[-1].time_from_start
        duration: float = last.sec + last.nanosec * 1e-9
        return duration
    return len(getattr(message, "poses", ())) * step_duration


def task_report(state: TaskEnd, failure_reason: str, opening: DoorOpening, autonomy: Autonomy,
                attempts: list[StateAttempt], robot_clock: str) -> TaskReport:
    """The TaskReport, saying which clock each time is on (docs/CLOCKS.md)."""
    from door_fsm.records import clocks_note

    return TaskReport(state, failure_reason, opening, autonomy, tuple(attempts), clocks_note(robot_clock))
