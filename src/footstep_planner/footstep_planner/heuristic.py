"""The A* heuristic: a lower bound of the cost still to pay, from the step limits.

Notation.  A search state is the support foot F just placed, with stance
centre c = c(F) and yaw theta = yaw(F).  Step i (i = 1..m) is taken from a
support foot of yaw theta_{i-1}; it moves the centre by dc_i, which is
``R(theta_{i-1}) delta_k`` for an action k (delta_k = (forward, +-outward)),
and turns by tau_i (|tau_i| <= A, the action set's ``max_turn``); it costs
``k_i = s + w_d |dc_i| + w_t |tau_i|`` (s = step_cost, w_d =
distance_weight, w_t = turn_weight).  A plan from F is m >= 0 such steps to
a state F_m passing the goal test (|c_m - g| <= e_p and
|wrap(theta_m - theta_g)| <= e_y), then the closing step (dc = 0, tau = 0,
cost s).

The heuristic::

    v = g - c,  psi = direction of v
    d = max(0, |v| - e_p)                       # distance still to cover
    a = max(0, |wrap(theta - theta_g)| - e_y)   # turn still to make
    n = max(N(d, theta - psi, theta_g - psi), ceil(a / A))
    h = s * (1 + n) + w_d * d + w_t * a

where N is the fewest steps whose *progress bound* P_m reaches d.

Progress bound.  Let ``G(alpha, r) = max over actions k and headings beta
with |beta - alpha| <= r of |delta_k| cos(beta + phi_k)`` (phi_k the
direction of delta_k): the most one step can advance the centre along psi
when the support heading relative to psi is within r of alpha.  Heading
theta_{i-1} is within (i - 1) A of theta (turns so far) and within
e_y + (m - i + 1) A of theta_g (turns still possible), so step i advances
the centre along psi by at most
``min(G(theta - psi, (i-1) A), G(theta_g - psi, e_y + (m-i+1) A))``, and
P_m is the sum of these bounds over i = 1..m.  P_m never decreases with m
(larger arcs, and the zero step is an action).

Admissible (h <= true remaining cost).  The final centre is within e_p of g,
so ``sum dc_i . u_psi = (c_m - c) . u_psi >= |v| - e_p``, hence P_m >= d and
m >= N.  On the circle ``sum |tau_i| >= a``, so m >= ceil(a / A).  Also
``sum |dc_i| >= |c_m - c| >= d``.  Adding the m step costs and the closing
step: ``cost >= s (m + 1) + w_d d + w_t a >= h``.  The table of P_m is built
on angle bins with every arc widened by half a bin, and beyond its last m
each further step adds at most max_k |delta_k|, so the tabulated N never
exceeds the true bound.

The simpler bound ``n = max(ceil(d / D), ceil(a / A))`` (D the largest
centre shift) is also admissible and *consistent*; the progress bound is
tighter (it knows that walking sideways or backwards is slower than forwards
and that turning takes steps) but only admissible, so the search re-opens a
state when it finds it again more cheaply.  With weight w > 1 (weighted A*,
f = g + w h) the plan costs at most w times the optimum.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from footstep_planner.footstep import Pose2D
from footstep_planner.geometry import FloatArray, wrap_angles
from footstep_planner.options import FootstepPlannerOptions

_ANGLE_BINS = 72
"""Bins of the progress table over each relative heading (5 degrees each)."""
_TABLE_STEPS = 24
"""Steps tabulated in the progress table; beyond, each step adds the largest centre shift."""


@dataclass(frozen=True, eq=False)
class ProgressTable:
    """P_m(alpha, beta) of the module docstring, tabulated.

    Attributes:
        progress: (M + 1, B, B) bound on the centre's advance along the goal
            direction in m steps, for relative heading bins alpha (now) and
            beta (goal).
        tail: (B,) bound on the advance in the first M steps, any goal heading.
        max_shift: the largest centre shift of one action (m).
    """

    progress: FloatArray
    tail: FloatArray
    max_shift: float
    _by_heading: FloatArray = field(init=False, repr=False)

    def __post_init__(self) -> None:
        rows = np.ascontiguousarray(self.progress.reshape(len(self.progress), -1).T)
        object.__setattr__(self, "_by_heading", rows)

    @classmethod
    def build(cls, centre_shifts: FloatArray, max_turn: float,
              yaw_tolerance: float) -> ProgressTable:
        """Tabulate from the actions' centre shifts (K, 2) in the support frame (both feet)."""
        width = 2.0 * math.pi / _ANGLE_BINS
        centres = -math.pi + (np.arange(_ANGLE_BINS) + 0.5) * width
        turns = np.arange(_TABLE_STEPS + 1) * max_turn + width / 2.0
        since_start = _best_advance(centre_shifts, centres, turns[:-1])
        before_goal = _best_advance(centre_shifts, centres, turns + yaw_tolerance)
        progress = np.zeros((_TABLE_STEPS + 1, _ANGLE_BINS, _ANGLE_BINS))
        for steps in range(1, _TABLE_STEPS + 1):
            bounds = np.minimum(since_start[:, None, :steps],
                                before_goal[None, :, steps:0:-1])
            progress[steps] = bounds.sum(axis=2)
        return cls(progress, since_start.sum(axis=1),
                   float(np.max(np.hypot(centre_shifts[:, 0], centre_shifts[:, 1]))))

    def min_steps(self, distance: FloatArray, alpha: FloatArray, beta: FloatArray) -> FloatArray:
        """N: fewest steps whose progress bound reaches ``distance`` (as floats)."""
        alpha_bin = _angle_bin(alpha)
        rows = self.by_heading[alpha_bin * _ANGLE_BINS + _angle_bin(beta)]
        steps = np.count_nonzero(rows < (distance - 1e-9)[:, None], axis=1).astype(float)
        beyond = steps > _TABLE_STEPS
        if np.any(beyond):
            rest = (distance[beyond] - self.tail[alpha_bin[beyond]]) / self.max_shift
            steps[beyond] = _TABLE_STEPS + np.maximum(np.ceil(rest - 1e-9), 1.0)
        return steps

    @property
    def by_heading(self) -> FloatArray:
        """The progress table as (B * B, M + 1) rows, one per (alpha, beta) bin pair."""
        return self._by_heading


def _best_advance(centre_shifts: FloatArray, headings: FloatArray, radii: FloatArray) -> FloatArray:
    """G(heading, radius) for every heading bin centre and radius, shape (B, R).

    An action of length rho and direction phi advances by rho cos(beta + phi)
    along the goal direction at relative heading beta; over the arc
    |beta - alpha| <= r that peaks at rho when -phi lies in the arc, else at
    the arc end nearest to -phi.
    """
    rho = np.hypot(centre_shifts[:, 0], centre_shifts[:, 1])
    phi = np.arctan2(centre_shifts[:, 1], centre_shifts[:, 0])
    offset = np.abs(wrap_angles(-phi[None, None, :] - headings[:, None, None]))
    outside = np.maximum(offset - radii[None, :, None], 0.0)
    return np.max(rho * np.cos(np.minimum(outside, math.pi)), axis=2)


def _angle_bin(angle: FloatArray) -> np.ndarray:
    """Progress-table bin of relative headings (rad, any turn: the bins wrap)."""
    width = 2.0 * math.pi / _ANGLE_BINS
    return np.floor((angle + math.pi) / width).astype(np.int64) % _ANGLE_BINS


@dataclass(frozen=True)
class FootstepHeuristic:
    """h for a goal; see the module docstring for the maths and the admissibility proof."""

    goal: Pose2D
    options: FootstepPlannerOptions
    table: ProgressTable
    max_turn: float
    """A: the largest yaw change of one action (rad)."""

    def remaining_distance(self, centre_x: FloatArray, centre_y: FloatArray) -> FloatArray:
        """d: distance of the stance centres beyond the goal tolerance (m)."""
        distance = np.hypot(centre_x - self.goal.x, centre_y - self.goal.y)
        return np.maximum(distance - self.options.goal_position_tolerance, 0.0)

    def remaining_turn(self, yaw: FloatArray) -> FloatArray:
        """a: yaw error beyond the goal tolerance (rad)."""
        error = np.abs(wrap_angles(yaw - self.goal.yaw))
        return np.maximum(error - self.options.goal_yaw_tolerance, 0.0)

    def estimate(self, centre_x: FloatArray, centre_y: FloatArray, yaw: FloatArray) -> FloatArray:
        """h for states with stance centres (centre_x, centre_y) and yaws ``yaw``."""
        options = self.options
        distance = self.remaining_distance(centre_x, centre_y)
        turn = self.remaining_turn(yaw)
        direction = np.arctan2(self.goal.y - centre_y, self.goal.x - centre_x)
        walking = self.table.min_steps(distance, yaw - direction, self.goal.yaw - direction)
        steps = np.maximum(walking, np.ceil(turn / self.max_turn - 1e-9))
        return (options.step_cost * (1.0 + steps) + options.distance_weight * distance
                + options.turn_weight * turn)

    def estimate_one(self, centre: Pose2D) -> float:
        """h of a single state whose stance centre pose is ``centre``."""
        return float(self.estimate(np.array([centre.x]), np.array([centre.y]),
                                   np.array([centre.yaw]))[0])


def is_goal_centre(centre: Pose2D, goal: Pose2D, options: FootstepPlannerOptions) -> bool:
    """The goal test on a stance centre: within the position and yaw tolerances.

    A 1e-9 slack absorbs float noise, so a centre exactly on the tolerance
    (where h has already dropped to the closing step alone) passes.
    """
    return (math.hypot(centre.x - goal.x, centre.y - goal.y)
            <= options.goal_position_tolerance + _SLACK
            and centre.yaw_difference(goal) <= options.goal_yaw_tolerance + _SLACK)


_SLACK = 1e-9
