"""Options of the footstep planner, validated on construction.

Defaults describe PAL's TALOS (the project's default robot): 0.22 x 0.13 m
soles, 0.20 m between the sole centres, 0.76 m wide with the arms tucked,
about 0.30 m deep.  Units are SI (m, rad, s); every field's docstring gives
its unit and the range enforced by :meth:`FootstepPlannerOptions.__post_init__`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

from footstep_planner.errors import FootstepPlannerError
from footstep_planner.validation import FieldRange, check_range

__all__ = ["FootstepPlannerOptions", "option_range"]


@dataclass(frozen=True)
class FootstepPlannerOptions:
    """Kinematic limits, robot dimensions, costs and search bounds.

    Step limits are displacements of the swing foot measured in the support
    foot's frame (x forward, y towards the swing foot's own side).
    """

    max_stride: float = 0.30
    """Longest forward step, swing-foot centre ahead of the support foot (m), (0, 1]."""
    max_backward_step: float = 0.15
    """Longest backward step (m), [0, 0.5]."""
    max_side_step: float = 0.15
    """Largest lateral step beyond the nominal separation (m), [0, 0.5]."""
    nominal_foot_separation: float = 0.20
    """Distance between the sole centres in the nominal stance (m), (0, 0.8]."""
    min_foot_separation: float = 0.16
    """Smallest lateral distance between sole centres; stops the legs crossing (m),
    [foot_width, nominal_foot_separation]."""
    max_turn: float = 0.35
    """Largest yaw change of one step (rad), (0, pi/2]."""
    foot_length: float = 0.22
    """Sole length (m), (0, 0.5]."""
    foot_width: float = 0.13
    """Sole width (m), (0, 0.3]."""
    foot_margin: float = 0.02
    """Clearance added around each sole for collision checks (m), [0, 0.2]."""
    body_half_width: float = 0.38
    """Half the body width across the shoulders, arms tucked (m), (0, 1]."""
    body_half_depth: float = 0.15
    """Half the body depth front to back (m), (0, 1]."""
    body_margin: float = 0.02
    """Clearance added around the body rectangle (m), [0, 0.2]."""
    body_offset: float = 0.0
    """The body rectangle's centre ahead of the stance centre (m), [-0.5, 0.5]: a robot
    whose arms reach further forward than its back (TALOS's grippers 0.28 m ahead, its
    torso 0.21 m behind) gets a box that fits it rather than one centred on the feet."""
    step_cost: float = 1.0
    """Fixed cost of every step (cost units), (0, 1000]."""
    distance_weight: float = 1.0
    """Cost per metre the stance centre moves (1/m), [0, 1000]."""
    turn_weight: float = 0.5
    """Cost per radian of turning (1/rad), [0, 1000]."""
    heuristic_weight: float = 1.0
    """Weight w of the heuristic: 1 is A* (optimal), > 1 weighted A* (cost <= w * optimal),
    [1, 10]."""
    max_expansions: int = 20_000
    """The search's budget: it stops with EXPANSION_LIMIT after this many expanded states,
    [1, 1e7].  Deterministic, so a plan never depends on CPU load: every passage leg and
    approach of the benchmark's full ranges needs a few hundred at most."""
    max_planning_time: float = 30.0
    """A safety net on wall time, far above normal use (plans take milliseconds): the search
    stops with TIME_LIMIT beyond it (s), (0, 600].  The budget is ``max_expansions``."""
    repeat_budget_growth: float = 2.0
    """Factor on max_expansions per repeat of a request (:mod:`~footstep_planner.attempts`),
    [1, 100]."""
    repeat_weight_step: float = 1.0
    """Added to heuristic_weight per repeat (a greedier search), [0, 9]."""
    repeat_margin_growth: float = 1.5
    """Factor on search_margin per repeat (a wider region), [1, 10]."""
    goal_position_tolerance: float = 0.05
    """Allowed distance of the final stance centre from the goal (m), (0, 1]."""
    goal_yaw_tolerance: float = 0.10
    """Allowed yaw error of the final stance (rad), (0, pi]."""
    snap_to_goal: bool = False
    """After the search, place both feet exactly on the goal's nominal stance with up to two
    more (small, checked) steps; for goals the arms work from, e.g. the stand pose."""
    grid_resolution: float = 0.025
    """Cell size of the closed set in x and y (m), (0, 0.5]."""
    yaw_resolution: float = 0.05
    """Cell size of the closed set in yaw (rad), (0, 0.5]."""
    search_margin: float = 2.0
    """The search stays within the box around start and goal grown by this (m), (0, 50]."""

    def __post_init__(self) -> None:
        for option in fields(self):
            if option.name == "snap_to_goal":
                if not isinstance(self.snap_to_goal, bool):
                    raise FootstepPlannerError(f"snap_to_goal must be a bool, got {self.snap_to_goal!r}")
                continue
            check_range(option.name, getattr(self, option.name), _RANGES[option.name],
                        integer=option.name in _INTEGERS)
        check_range("min_foot_separation", self.min_foot_separation,
                    FieldRange(self.foot_width, self.nominal_foot_separation, "m"))

    @property
    def body_reach_depth(self) -> float:
        """Half depth, margin included, of the box centred on the stance centre that holds the
        body box wherever its offset puts it: b + |offset| + margin (m)."""
        return self.body_half_depth + abs(self.body_offset) + self.body_margin

    @property
    def max_stance_separation(self) -> float:
        """Largest lateral distance between sole centres after a side step (m)."""
        return self.nominal_foot_separation + self.max_side_step


_RANGES: dict[str, FieldRange] = {
    "max_stride": FieldRange(0.0, 1.0, "m", low_open=True),
    "max_backward_step": FieldRange(0.0, 0.5, "m"),
    "max_side_step": FieldRange(0.0, 0.5, "m"),
    "nominal_foot_separation": FieldRange(0.0, 0.8, "m", low_open=True),
    "min_foot_separation": FieldRange(0.0, 0.8, "m", low_open=True),
    "max_turn": FieldRange(0.0, math.pi / 2.0, "rad", low_open=True),
    "foot_length": FieldRange(0.0, 0.5, "m", low_open=True),
    "foot_width": FieldRange(0.0, 0.3, "m", low_open=True),
    "foot_margin": FieldRange(0.0, 0.2, "m"),
    "body_half_width": FieldRange(0.0, 1.0, "m", low_open=True),
    "body_half_depth": FieldRange(0.0, 1.0, "m", low_open=True),
    "body_margin": FieldRange(0.0, 0.2, "m"),
    "body_offset": FieldRange(-0.5, 0.5, "m"),
    "step_cost": FieldRange(0.0, 1000.0, "", low_open=True),
    "distance_weight": FieldRange(0.0, 1000.0, "1/m"),
    "turn_weight": FieldRange(0.0, 1000.0, "1/rad"),
    "heuristic_weight": FieldRange(1.0, 10.0, ""),
    "max_expansions": FieldRange(1, 10_000_000, "expansions"),
    "max_planning_time": FieldRange(0.0, 600.0, "s", low_open=True),
    "repeat_budget_growth": FieldRange(1.0, 100.0, ""),
    "repeat_weight_step": FieldRange(0.0, 9.0, ""),
    "repeat_margin_growth": FieldRange(1.0, 10.0, ""),
    "goal_position_tolerance": FieldRange(0.0, 1.0, "m", low_open=True),
    "goal_yaw_tolerance": FieldRange(0.0, math.pi, "rad", low_open=True),
    "grid_resolution": FieldRange(0.0, 0.5, "m", low_open=True),
    "yaw_resolution": FieldRange(0.0, 0.5, "rad", low_open=True),
    "search_margin": FieldRange(0.0, 50.0, "m", low_open=True),
}
_INTEGERS = frozenset({"max_expansions"})
"""The options that must be ``int``."""


def option_range(name: str) -> FieldRange:
    """The allowed range of option ``name`` (fixed ranges only; min_foot_separation's depends
    on other fields)."""
    return _RANGES[name]

