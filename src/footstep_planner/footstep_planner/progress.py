"""The heuristic's progress bound: how far m steps can carry the stance centre towards a goal.

A search state is the support foot just placed, heading theta; the goal lies in
direction psi. Step i swings foot f_i (the feet alternate, starting with the state's
next swing foot), taken from support heading theta_{i-1}; its action k moves the
centre by ``R(theta_{i-1}) delta_k`` (delta_k of length rho_k, direction phi_k, in the
support frame) and turns the heading by tau_k. Its advance along psi is

    rho_k cos(theta_{i-1} - psi + phi_k).

P_m(alpha, beta) bounds the total advance of m steps from relative heading alpha =
theta - psi that end within e_y of the goal's relative heading beta = theta_g - psi.
It is the exact maximum over all such step sequences, computed by dynamic programming
over the heading, which every action changes by its own turn:

    F_0(h; beta)   = 0 if |h - beta| <= e_y, else -inf,
    F_j^f(h; beta) = max over actions k of foot f of
                     rho_k cos(h + phi_k) + F_{j-1}^{other f}(h + tau_k; beta),
    P_m^f          = F_m^f.

So a side step, which does not turn, cannot also turn the body to walk forwards: an
earlier bound that let every step take the best advance at any heading reachable by
then (decoupling each step's action from its turn) said 8 steps for a 1.2 m sideways
move that needs 14, and the search expanded 50,000 states. The feet alternate in the
recursion: walking left, the left foot side-steps by up to ``max_side_step`` but the
right can only follow with the inward step, so a pair advances max_side_step +
(nominal - min separation), not twice max_side_step.

Discretisation (admissible).  Headings live on B bins of width w = 2 pi / B with
B = 4 round(2 pi / A), so a turn of A is 4 bins up to a drift e = |A - 4 w| per step
(A the largest turn; each action's turn is rounded to whole bins, with the largest
rounding error taken as e). After j <= M steps the true heading is within
r = w / 2 + M e of the tracked bin centre, so each bin's advance is the maximum over
that arc, and the end test is widened by r + w / 2 (beta is binned too). The DP
therefore never underestimates the true maximum: P_m >= the advance of every feasible
sequence. P_m never decreases with m (appending the zero step keeps any sequence
feasible). Beyond M steps, each further step adds at most the largest centre shift.

Yaw window W (:mod:`~footstep_planner.pruning`): every heading of the sequence stays
within W of the goal's, so bins farther than W + r + w / 2 from beta are -inf at every
step.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

import numpy as np

from footstep_planner.footstep import Foot
from footstep_planner.geometry import FloatArray, wrap_angles

TABLE_STEPS = 48
"""M: steps tabulated (a 2 m sideways leg takes about 36)."""


@dataclass(frozen=True)
class StepEffects:
    """What the actions of one swing foot do: centre shifts (K, 2) in the support frame and
    heading changes (K,) (rad)."""

    shifts: FloatArray
    turns: FloatArray


@dataclass(frozen=True, eq=False)
class ProgressTable:
    """P_m^f(alpha, beta) of the module docstring, tabulated.

    Attributes:
        rows: per next swing foot f, (B * B, M + 1): row alpha_bin * B + beta_bin holds
            P_0..P_M (-inf where the goal heading cannot be reached in m steps).
        tail: per f, (B,) the most the first M steps can advance, any final heading.
        max_shift: the largest centre shift of one action (m).
        bins: B.
    """

    rows: Mapping[Foot, FloatArray]
    tail: Mapping[Foot, FloatArray]
    max_shift: float
    bins: int

    @classmethod
    def build(cls, effects: Mapping[Foot, StepEffects], max_turn: float, yaw_tolerance: float,
              yaw_window: float = math.pi) -> ProgressTable:
        """Run the DP for both feet (see the module docstring)."""
        bins = 4 * max(1, round(2.0 * math.pi / max_turn))
        width = 2.0 * math.pi / bins
        turn_bins = {foot: np.rint(e.turns / width).astype(np.int64) for foot, e in effects.items()}
        drift = max(float(np.max(np.abs(e.turns - turn_bins[foot] * width))) for foot, e in effects.items())
        slack = width / 2.0 + TABLE_STEPS * drift
        centres = -math.pi + (np.arange(bins) + 0.5) * width
        gap = np.abs(wrap_angles(centres[:, None] - centres[None, :]))  # (heading bin, goal bin)
        allowed = gap <= yaw_window + slack + width / 2.0
        advance = {foot: _advance_by_turn(e, turn_bins[foot], centres, slack) for foot, e in effects.items()}
        ending = np.where(gap <= yaw_tolerance + slack + width / 2.0, 0.0, -np.inf)
        tables = _recurse(advance, np.where(allowed, ending, -np.inf), allowed)
        rows = {foot: np.ascontiguousarray(table.reshape(TABLE_STEPS + 1, -1).T) for foot, table in tables.items()}
        # every sequence ends near some goal bin, so the best over them bounds any ending
        tail = {foot: table[-1].max(axis=1) for foot, table in tables.items()}
        shifts = np.concatenate([e.shifts for e in effects.values()])
        return cls(MappingProxyType(rows), MappingProxyType(tail),
                   float(np.max(np.hypot(shifts[:, 0], shifts[:, 1]))), bins)

    def min_steps(self, distance: FloatArray, alpha: FloatArray, beta: FloatArray,
                  next_swing: Foot) -> FloatArray:
        """N: fewest steps, the first swinging ``next_swing``, whose bound reaches
        ``distance`` (as floats); alpha, beta as in the module docstring (rad)."""
        alpha_bin = self.bin_of(alpha)
        rows = self.rows[next_swing][alpha_bin * self.bins + self.bin_of(beta)]
        steps = np.count_nonzero(rows < (distance - 1e-9)[:, None], axis=1).astype(float)
        beyond = steps > TABLE_STEPS
        if np.any(beyond):
            rest = (distance[beyond] - self.tail[next_swing][alpha_bin[beyond]]) / self.max_shift
            steps[beyond] = TABLE_STEPS + np.maximum(np.ceil(rest - 1e-9), 1.0)
        return steps

    def bin_of(self, angle: FloatArray) -> np.ndarray:
        """Heading bin of relative angles (rad, any turn: the bins wrap)."""
        width = 2.0 * math.pi / self.bins
        return np.floor((np.asarray(angle) + math.pi) / width).astype(np.int64) % self.bins


def _advance_by_turn(effects: StepEffects, turn_bins: np.ndarray, centres: FloatArray,
                     slack: float) -> dict[int, FloatArray]:
    """For each turn (in bins) of this foot's actions, the best advance along psi from each
    heading bin: max over those actions and the arc of radius ``slack`` about the bin centre."""
    return {int(turn): _best_advance(effects.shifts[turn_bins == turn], centres, slack)
            for turn in np.unique(turn_bins)}


def _best_advance(shifts: FloatArray, headings: FloatArray, radius: float) -> FloatArray:
    """max over actions and |beta - heading| <= radius of rho cos(beta + phi), shape (B,).

    rho cos(beta + phi) peaks at rho where beta = -phi; over an arc it peaks at the arc
    point nearest to -phi.
    """
    rho = np.hypot(shifts[:, 0], shifts[:, 1])
    phi = np.arctan2(shifts[:, 1], shifts[:, 0])
    offset = np.abs(wrap_angles(-phi[None, :] - headings[:, None]))
    outside = np.maximum(offset - radius, 0.0)
    return np.max(rho * np.cos(np.minimum(outside, math.pi)), axis=1)


def _recurse(advance: Mapping[Foot, dict[int, FloatArray]], start: FloatArray,
             allowed: np.ndarray) -> dict[Foot, FloatArray]:
    """F_0..F_M of both feet from F_0 = ``start`` (heading bin, goal bin); headings outside
    ``allowed`` are -inf at every step."""
    tables = {foot: np.empty((TABLE_STEPS + 1, *start.shape)) for foot in Foot}
    for foot in Foot:
        tables[foot][0] = start
    bins = start.shape[0]
    shifted = {foot: {turn: (np.arange(bins) + turn) % bins for turn in gains} for foot, gains in advance.items()}
    for step in range(1, TABLE_STEPS + 1):
        for foot in Foot:
            previous = tables[foot.other][step - 1]
            best = np.full(start.shape, -np.inf)
            for turn, gain in advance[foot].items():  # heading bin h continues from h + turn
                np.maximum(best, gain[:, None] + previous[shifted[foot][turn]], out=best)
            tables[foot][step] = np.where(allowed, best, -np.inf)
    return tables
