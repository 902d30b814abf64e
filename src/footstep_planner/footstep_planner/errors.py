"""Errors raised by the footstep planner core.

Bad *configuration* (an option out of range, a malformed door) raises
:class:`FootstepPlannerError`; bad *planning input* (NaN goal, goal inside a
wall, unreachable goal) never raises: the planner returns a failure
:class:`~footstep_planner.plan.PlanOutcome` with a human-readable reason, so a
node can publish it and keep running.

:class:`FootstepPlannerError` is the package's one base error. It is not a
:class:`ValueError`: the node reports it as a REJECTED request, and a ``ValueError`` from a
bug must instead end as a FAILURE ("internal error").
"""

from __future__ import annotations

__all__ = ["FootstepPlannerError", "NoWalkForDoor", "RequestRefused"]


class FootstepPlannerError(Exception):
    """A value given to the footstep planner core is invalid.

    ``field`` names the offending option or argument (empty when the error is
    not about one field), so a ROS node can map it back to its parameter.
    """

    def __init__(self, message: str, field: str = "") -> None:
        super().__init__(message)
        self.field = field


class RequestRefused(FootstepPlannerError):
    """A request that cannot be planned from the node's inputs (no odometry yet, no usable
    door estimate): answered REJECTED with this reason."""


class NoWalkForDoor(Exception):
    """A request for a walk this door's passage does not have (a narrow push door's doorway
    walk: it is side-stepped through in one go): answered SKIPPED with this reason, and the FSM
    goes on past that part of the passage. Not a :class:`FootstepPlannerError`: nothing was
    wrong with the request."""
