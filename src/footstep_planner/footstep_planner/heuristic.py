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

where N is the fewest steps whose *progress bound* P_m reaches d: the most m
steps starting with the state's next swing foot can advance the centre along
psi and still end within e_y of the goal's heading
(:class:`~footstep_planner.progress.ProgressTable`, a dynamic programme over
the heading that couples each step's advance to its own turn).

Admissible (h <= true remaining cost).  The final centre is within e_p of g,
so ``sum dc_i . u_psi = (c_m - c) . u_psi >= |v| - e_p``, hence P_m >= d and
m >= N (the table never underestimates P_m, see its module).  On the circle
``sum |tau_i| >= a``, so m >= ceil(a / A).  Also ``sum |dc_i| >= |c_m - c| >=
d``.  Adding the m step costs and the closing step:
``cost >= s (m + 1) + w_d d + w_t a >= h``.

The simpler bound ``n = max(ceil(d / D), ceil(a / A))`` (D the largest
centre shift) is also admissible and *consistent*; the progress bound is
tighter (it knows that walking sideways or backwards is slower than forwards
and that turning takes steps) but only admissible, so the search re-opens a
state when it finds it again more cheaply.  With weight w > 1 (weighted A*,
f = g + w h) the plan costs at most w times the optimum.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from door_contract.vocabulary import Foot
from footstep_planner.footstep import Pose2D
from footstep_planner.geometry import FloatArray, wrap_angles
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.progress import ProgressTable

__all__ = ["FootstepHeuristic", "is_goal_centre"]


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
        beyond_tolerance: FloatArray = np.maximum(distance - self.options.goal_position_tolerance, 0.0)
        return beyond_tolerance

    def remaining_turn(self, yaw: FloatArray) -> FloatArray:
        """a: yaw error beyond the goal tolerance (rad)."""
        error = np.abs(wrap_angles(yaw - self.goal.yaw))
        return np.maximum(error - self.options.goal_yaw_tolerance, 0.0)

    def estimate(self, centre_x: FloatArray, centre_y: FloatArray, yaw: FloatArray,
                 next_swing: Foot) -> FloatArray:
        """h for states with stance centres (centre_x, centre_y) and yaws ``yaw`` whose next
        step swings ``next_swing``."""
        options = self.options
        distance = self.remaining_distance(centre_x, centre_y)
        turn = self.remaining_turn(yaw)
        direction = np.arctan2(self.goal.y - centre_y, self.goal.x - centre_x)
        walking = self.table.min_steps(distance, yaw - direction, self.goal.yaw - direction,
                                       next_swing)
        steps = np.maximum(walking, np.ceil(turn / self.max_turn - 1e-9))
        estimates: FloatArray = (options.step_cost * (1.0 + steps) + options.distance_weight * distance
                                 + options.turn_weight * turn)
        return estimates

    def estimate_one(self, centre: Pose2D, next_swing: Foot) -> float:
        """h of a single state whose stance centre pose is ``centre``."""
        return float(self.estimate(np.array([centre.x]), np.array([centre.y]),
                                   np.array([centre.yaw]), next_swing)[0])


def is_goal_centre(centre: Pose2D, goal: Pose2D, options: FootstepPlannerOptions) -> bool:
    """The goal test on a stance centre: within the position and yaw tolerances.

    A 1e-9 slack absorbs float noise, so a centre exactly on the tolerance
    (where h has already dropped to the closing step alone) passes.
    """
    return (math.hypot(centre.x - goal.x, centre.y - goal.y)
            <= options.goal_position_tolerance + _SLACK
            and centre.yaw_difference(goal) <= options.goal_yaw_tolerance + _SLACK)


_SLACK = 1e-9
