"""Snapping: the last steps of a walk that must end exactly on its goal (the stand pose,
the legs of a walk through waypoints), after the search has stopped within its tolerance."""

from __future__ import annotations

from footstep_planner.actions import is_reachable_step
from footstep_planner.footprint import FootprintChecker
from footstep_planner.footstep import Footstep, Pose2D, Stance
from footstep_planner.options import FootstepPlannerOptions

__all__ = ["snapping_steps"]


def snapping_steps(last: Footstep, goal: Pose2D, options: FootstepPlannerOptions,
                   checker: FootprintChecker) -> tuple[Footstep, ...]:
    """Steps from the search's final stance (within the goal tolerance) onto the goal's
    nominal stance. Feet alternate, so the foot that did not move last goes first; when
    it cannot reach its target from there (a sideways shift towards it), it first steps
    in place and the other foot leads. Empty when no sequence stays within the step
    limits and clear of obstacles (the plan then ends within the tolerance)."""
    separation = options.nominal_foot_separation
    target = Stance.nominal(goal, separation)
    if target.foot(last.foot) == last and target.foot(last.foot.other) == last.nominal_partner(separation):
        return ()
    if checker.stance_collision(target) is not None:
        return ()
    in_place = last.nominal_partner(separation)
    for sequence in ((target.foot(last.foot.other), target.foot(last.foot)),
                     (in_place, target.foot(last.foot), target.foot(last.foot.other))):
        if _walkable(last, sequence, options, checker):
            return sequence
    return ()


def _walkable(support: Footstep, sequence: tuple[Footstep, ...], options: FootstepPlannerOptions,
              checker: FootprintChecker) -> bool:
    for placed in sequence:
        if not is_reachable_step(support, placed, options) or checker.footstep_collides(placed):
            return False
        support = placed
    return True
