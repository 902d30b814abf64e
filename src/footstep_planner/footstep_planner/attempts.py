"""Repeats that change something: the search settings of the n-th attempt at a request.

The FSM repeats a state that failed (``FootstepRequest.attempt``: 0 for the first try, +1
per repeat) after re-reading the robot's state; sending the planner the same search again
would fail the same way, since every search is deterministic. So attempt n searches
differently from attempt n - 1, in three ways:

* a larger budget: ``max_expansions * repeat_budget_growth ** n``;
* a greedier search: heuristic weight ``w + n * repeat_weight_step`` (capped at 10).
  Weighted A* with weight w expands the states with f = g + w h in order, so a larger w
  dives deeper towards the goal for the same number of expansions, at a plan cost still
  within w times the optimum;
* a wider region: ``search_margin * repeat_margin_growth ** n`` (capped at 50 m), for a goal
  reached only by a detour beyond the first search's box.

Each setting is capped by its option's range; beyond the attempt at which all three are at
their caps a repeat cannot change anything, and :func:`options_for_attempt` refuses it.
"""

from __future__ import annotations

from dataclasses import replace

from footstep_planner.errors import FootstepPlannerError
from footstep_planner.options import FootstepPlannerOptions, option_range
from footstep_planner.validation import FieldRange, check_range

__all__ = ["MAX_ATTEMPT", "options_for_attempt"]

MAX_ATTEMPT = 20
"""Highest attempt number accepted."""


def options_for_attempt(options: FootstepPlannerOptions, attempt: int) -> FootstepPlannerOptions:
    """The options of attempt ``attempt`` (0 = ``options`` themselves; see the module docstring).

    Raises :class:`FootstepPlannerError` for an attempt that is not an integer in
    [0, MAX_ATTEMPT], or that could not differ from its predecessor.
    """
    if isinstance(attempt, bool) or not isinstance(attempt, int):
        raise FootstepPlannerError(f"attempt must be an integer, got {attempt!r}", field="attempt")
    check_range("attempt", attempt, FieldRange(0, MAX_ATTEMPT, "repeats"))
    if attempt == 0:
        return options
    repeated = _scaled(options, attempt)
    if repeated == _scaled(options, attempt - 1):
        raise FootstepPlannerError(
            f"attempt {attempt} would search exactly as attempt {attempt - 1}: budget, heuristic "
            "weight and search margin are all at their limits", field="attempt")
    return repeated


def _scaled(options: FootstepPlannerOptions, attempt: int) -> FootstepPlannerOptions:
    """The three settings of attempt ``attempt``, each clipped to its option's range."""
    if attempt == 0:
        return options
    budget = options.max_expansions * options.repeat_budget_growth ** attempt
    weight = options.heuristic_weight + attempt * options.repeat_weight_step
    margin = options.search_margin * options.repeat_margin_growth ** attempt
    return replace(options, max_expansions=int(min(budget, option_range("max_expansions").high)),
                   heuristic_weight=min(weight, option_range("heuristic_weight").high),
                   search_margin=min(margin, option_range("search_margin").high))
