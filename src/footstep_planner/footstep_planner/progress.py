"""The heuristic's progress bound: how far m steps can carry the stance centre towards a goal.

A search state is the support foot just placed, heading theta; the goal lies in
direction psi. Step i swings foot f_i (the feet alternate, starting with the state's
next swing foot), taken from support heading theta_{i-1}; its action k moves the
centre by ``R(theta_{i-1}) delta_k`` (delta_k of length rho_k, direction phi_k, in the
support frame) and turns the heading by tau_k. Its advance along psi is

    rho_k cos(theta_{i-1} - psi + phi_k).

P_m(alpha, beta) bounds the total advance of m steps from relative heading alpha =
theta - psi that end within e_y of the goal's relative heading beta = theta_g - psi.
It is the maximum over all such step sequences, computed by dynamic programming over
the heading, which every action changes by its own turn (written backwards; see
Discretisation for the forward form used without a yaw window):

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
rounding error taken as e). After i steps the true heading is within slack(i) =
w / 2 + i e of the tracked bin centre. The table is computed forwards from the start
heading bin alpha, V_i(alpha, h) being the most i steps can advance ending in bin h:
step i maximises its advance over the arc of radius slack(i - 1) about its bin centre,
and P_m(alpha, beta) is the best V_m over the bins within e_y + w + m e of beta (the
goal heading is binned too). So the DP never underestimates the true maximum: P_m >=
the advance of every feasible sequence. (With the drift of M = 48 steps everywhere, as a
backward recursion over the steps still to go would need, the arcs grew by 0.09 rad for
TALOS and the searches expanded twice as many states.) P_m never decreases with m
(appending the zero step keeps any sequence feasible). Beyond M steps, each further step
adds at most the largest centre shift.

Yaw window W (:mod:`~footstep_planner.pruning`): every heading of the sequence stays
within W of the goal's. That couples every step to beta, so windowed tables use the
recursion above backwards from the goal (F_j over (h, beta)), with bins farther than
W + slack(M) + w / 2 from beta at -inf at every step and the drift of M steps on every arc.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

import numpy as np

from door_contract.vocabulary import Foot
from footstep_planner.geometry import FloatArray, wrap_angles

__all__ = ["ProgressTable", "StepEffects"]

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
        grid = _HeadingGrid(bins, width, drift)
        if yaw_window >= math.pi:
            tables = _forward(effects, turn_bins, grid, yaw_tolerance)
        else:
            tables = _backward(effects, turn_bins, grid, yaw_tolerance, yaw_window)
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
        steps: FloatArray = np.count_nonzero(rows < (distance - 1e-9)[:, None], axis=1).astype(float)
        beyond = steps > TABLE_STEPS
        if np.any(beyond):
            rest = (distance[beyond] - self.tail[next_swing][alpha_bin[beyond]]) / self.max_shift
            steps[beyond] = TABLE_STEPS + np.maximum(np.ceil(rest - 1e-9), 1.0)
        return steps

    def bin_of(self, angle: FloatArray) -> np.ndarray:
        """Heading bin of relative angles (rad, any turn: the bins wrap)."""
        width = 2.0 * math.pi / self.bins
        bins: np.ndarray = np.floor((np.asarray(angle) + math.pi) / width).astype(np.int64) % self.bins
        return bins


@dataclass(frozen=True)
class _HeadingGrid:
    """B heading bins of ``width`` (rad); ``drift``: the most one step's turn differs from its
    whole number of bins (rad)."""

    bins: int
    width: float
    drift: float

    @property
    def centres(self) -> FloatArray:
        return -math.pi + (np.arange(self.bins) + 0.5) * self.width

    def slack(self, steps: int) -> float:
        """How far the true heading can be from its tracked bin centre after ``steps`` steps."""
        return self.width / 2.0 + steps * self.drift


def _advance_by_turn(effects: StepEffects, turn_bins: np.ndarray, centres: FloatArray,
                     slack: float) -> dict[int, FloatArray]:
    """For each turn (in bins) of this foot's actions, the best advance along psi from each
    heading bin: max over those actions and the arc of radius ``slack`` about the bin centre."""
    return {int(turn): _best_advance(effects.shifts[turn_bins == turn], centres, slack)
            for turn in np.unique(turn_bins)}


def _forward(effects: Mapping[Foot, StepEffects], turn_bins: Mapping[Foot, np.ndarray], grid: _HeadingGrid,
             yaw_tolerance: float) -> dict[Foot, FloatArray]:
    """P_0..P_M of both first feet by a forward DP from the start heading (no yaw window).

    V_i(alpha, h): the most i steps from heading bin alpha can advance, ending in bin h. Step
    i is taken after i - 1 rounded turns, so its advance is maximised over the arc of radius
    slack(i - 1) only (not the worst case of M steps), and P_m(alpha, beta) is the best V_m
    over the bins h within e_y + w + m e of beta (the true final heading is within
    slack(m) of h's centre, the goal's within w / 2 of beta's).
    """
    bins, centres = grid.bins, grid.centres
    gains = {foot: [_advance_by_turn(e, turn_bins[foot], centres, grid.slack(step)) for step in range(TABLE_STEPS)]
             for foot, e in effects.items()}
    tables: dict[Foot, FloatArray] = {}
    for first in Foot:
        reach = np.full((bins, bins), -np.inf)
        np.fill_diagonal(reach, 0.0)
        table = np.empty((TABLE_STEPS + 1, bins, bins))
        table[0] = _best_near(reach, _end_bins(grid, yaw_tolerance, 0))
        for step in range(1, TABLE_STEPS + 1):
            foot = first if step % 2 == 1 else first.other
            moved = np.full((bins, bins), -np.inf)
            for turn, gain in gains[foot][step - 1].items():  # from bin h to bin h + turn
                np.maximum(moved, np.roll(reach + gain[None, :], turn, axis=1), out=moved)
            reach = moved
            table[step] = _best_near(reach, _end_bins(grid, yaw_tolerance, step))
        tables[first] = table
    return tables


def _end_bins(grid: _HeadingGrid, yaw_tolerance: float, steps: int) -> int:
    """Bins either side of the goal's bin that an end heading may lie in after ``steps``."""
    return int(math.floor((yaw_tolerance + grid.width / 2.0 + grid.slack(steps)) / grid.width + 1e-9))


def _best_near(reach: FloatArray, spread: int) -> FloatArray:
    """(alpha, beta): the best of ``reach[alpha, h]`` over the bins h within ``spread`` of beta."""
    best = reach.copy()
    for offset in range(1, spread + 1):
        np.maximum(best, np.roll(reach, offset, axis=1), out=best)
        np.maximum(best, np.roll(reach, -offset, axis=1), out=best)
    return best


def _backward(effects: Mapping[Foot, StepEffects], turn_bins: Mapping[Foot, np.ndarray], grid: _HeadingGrid,
              yaw_tolerance: float, yaw_window: float) -> dict[Foot, FloatArray]:
    """P_0..P_M within a yaw window, by the backward DP of the module docstring: every heading
    of the sequence within the window of the goal's, with the drift of M steps everywhere."""
    slack, centres = grid.slack(TABLE_STEPS), grid.centres
    gap = np.abs(wrap_angles(centres[:, None] - centres[None, :]))  # (heading bin, goal bin)
    allowed = gap <= yaw_window + slack + grid.width / 2.0
    advance = {foot: _advance_by_turn(e, turn_bins[foot], centres, slack) for foot, e in effects.items()}
    ending = np.where(gap <= yaw_tolerance + slack + grid.width / 2.0, 0.0, -np.inf)
    return _recurse(advance, np.where(allowed, ending, -np.inf), allowed)


def _best_advance(shifts: FloatArray, headings: FloatArray, radius: float) -> FloatArray:
    """max over actions and |beta - heading| <= radius of rho cos(beta + phi), shape (B,).

    rho cos(beta + phi) peaks at rho where beta = -phi; over an arc it peaks at the arc
    point nearest to -phi.
    """
    rho = np.hypot(shifts[:, 0], shifts[:, 1])
    phi = np.arctan2(shifts[:, 1], shifts[:, 0])
    offset = np.abs(wrap_angles(-phi[None, :] - headings[:, None]))
    outside = np.maximum(offset - radius, 0.0)
    peaks: FloatArray = np.max(rho * np.cos(np.minimum(outside, math.pi)), axis=1)
    return peaks


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
