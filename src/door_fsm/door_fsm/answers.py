"""What the robot's and the planners' answers mean to the machine: messages → events, ROS-free.

A slipped hand is a HandSlipped whatever the status; a fall ends the task (no repeat); any
other status but success is a failed execution, with the status and reason for the log
and the report.
"""

from __future__ import annotations

from door_contract.door_estimates import door_estimate_problem
from door_contract.errors import ContractError
from door_contract.payloads import DoorEstimate, ExecutionOutcome, OutcomeStatus, PlanningOutcome, decode
from door_fsm import events as ev
from door_fsm.exchange import Proposal
from door_fsm.summaries import plan_summary

__all__ = ["execution_event", "planning_event", "usable_door_estimate"]


def execution_event(outcome: ExecutionOutcome, request_id: int) -> ev.Event:
    if outcome.slipped:
        return ev.HandSlipped(outcome.reason)
    fell = outcome.status is OutcomeStatus.FELL  # the reason is then how it fell ("base tilted 35°")
    reason = outcome.reason if fell else f"{outcome.status.value}: {outcome.reason}"
    return ev.ExecutionFinished(request_id, outcome.status is OutcomeStatus.SUCCESS, reason, fell=fell)


def planning_event(answer: Proposal | PlanningOutcome) -> ev.Event:
    """A paired proposal is ready; a bare outcome is the current request's skip or failure."""
    if isinstance(answer, Proposal):
        return ev.ProposalReady(answer.request_id, plan_summary(answer.outcome), answer.work_s)
    if answer.status is OutcomeStatus.SKIPPED:
        return ev.ProposalSkipped(answer.request_id, answer.reason)
    return ev.ProposalFailed(answer.request_id, f"{answer.status.value}: {answer.reason}")


def usable_door_estimate(text: str) -> DoorEstimate:
    """The estimate in ``text`` if a planner can use it, else :class:`ContractError` saying why."""
    estimate = decode(DoorEstimate, text)
    problem = door_estimate_problem(estimate)
    if problem:
        raise ContractError(problem)
    return estimate
