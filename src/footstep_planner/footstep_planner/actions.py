"""The action set: the steps the planner may take, relative to the support foot.

An action is described by what it does to the *stance centre*: with support
foot F, c(F) is the body pose of the nominal stance on F (F shifted half the
nominal separation towards the swing side, see
:meth:`~footstep_planner.footstep.Footstep.stance_centre`).  An action moves
that centre by ``forward`` along F's x axis and ``outward`` towards the swing
foot's side, and turns the new foot by ``turn`` towards the swing side
(toe out).  The swing foot F' then lands where c(F') is the moved centre:

    swing = (forward - sin(turn) * d/2,  sigma * (d/2 + outward + cos(turn) * d/2)),
    yaw(swing) = sigma * turn,

in F's frame, with d the nominal separation and sigma = +1 for a left swing
foot, -1 for a right one (the right foot's actions mirror the left's).
So ``(0, 0, 0)`` is the closing step to the nominal stance, and pure turns
rotate the stance about its centre without moving it.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

import numpy as np

from door_contract.vocabulary import Foot
from footstep_planner.footstep import Footstep
from footstep_planner.geometry import (
    FloatArray,
    PackedPolygons,
    rectangle_axes,
    rectangle_corners,
    rectangles_overlap_polygons,
)
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.progress import StepEffects

__all__ = ["CLEARANCE_STEP", "CLOSING_STEP", "ActionSet", "ActionTable", "StepAction", "candidate_actions",
           "cleared_turn", "is_kinematically_valid", "is_reachable_step"]


@dataclass(frozen=True)
class StepAction:
    """One step, as a move of the stance centre (see the module docstring).

    ``forward`` (m) along the support foot, ``outward`` (m) towards the swing
    side, ``turn`` (rad) of the swing foot towards its own side.
    """

    forward: float
    outward: float
    turn: float

    def swing_offset(self, swing_foot: Foot, separation: float) -> tuple[float, float, float]:
        """Swing-foot pose (x, y, yaw) in the support foot's frame."""
        sign = swing_foot.sign
        half = separation / 2.0
        return (self.forward - math.sin(self.turn) * half,
                sign * (half + self.outward + math.cos(self.turn) * half),
                sign * self.turn)

    def centre_offset(self, swing_foot: Foot, separation: float) -> tuple[float, float]:
        """The new stance centre c(F') in the support foot's frame."""
        return (self.forward, swing_foot.sign * (separation / 2.0 + self.outward))

    @property
    def centre_shift(self) -> float:
        """How far the stance centre moves (m)."""
        return math.hypot(self.forward, self.outward)

    def cost(self, options: FootstepPlannerOptions) -> float:
        """step_cost + distance_weight * |centre shift| + turn_weight * |turn|."""
        return (options.step_cost + options.distance_weight * self.centre_shift
                + options.turn_weight * abs(self.turn))


CLOSING_STEP = StepAction(0.0, 0.0, 0.0)
"""Places the swing foot beside the support foot in the nominal stance."""


CLEARANCE_STEP = 0.005
"""Resolution (m) of the outward shift that lets a turning sole clear the support sole."""


def candidate_actions(options: FootstepPlannerOptions) -> tuple[StepAction, ...]:
    """Straight steps, side steps, diagonal steps and turns scaled to the options' limits.

    Forward lengths are sixths of ``max_stride`` and thirds of
    ``max_backward_step`` (0.05 m apart for TALOS); side steps are thirds of
    ``max_side_step`` plus one inward step to ``min_foot_separation``; turns
    are +-max_turn and +-max_turn/2, in place and walking, each moved outward
    just enough to clear the support sole (:func:`cleared_turn`).
    """
    stride, back, side, turn = (options.max_stride, options.max_backward_step,
                                options.max_side_step, options.max_turn)
    forwards = [stride * k / 6.0 for k in range(6, 0, -1)] + [0.0] + [-back * k / 3.0
                                                                      for k in (1, 2, 3)]
    actions = [StepAction(f, 0.0, 0.0) for f in forwards]
    actions += [StepAction(0.0, side * k / 3.0, 0.0) for k in (1, 2, 3)]
    inward = options.min_foot_separation - options.nominal_foot_separation
    actions += [StepAction(0.0, inward, 0.0)] if inward < 0.0 else []
    actions += [StepAction(stride * i / 3.0, side * j / 3.0, 0.0) for i in (1, 2) for j in (1, 2)]
    turns = (cleared_turn(StepAction(stride * f, 0.0, sign * turn * t), options)
             for f in (0.0, 0.5, 5.0 / 6.0) for t in (0.5, 1.0) for sign in (1.0, -1.0))
    actions += [a for a in turns if a is not None]
    unique = dict.fromkeys(actions)  # keeps order, drops duplicates (e.g. zero side step)
    return tuple(a for a in unique if is_kinematically_valid(a, options))


def cleared_turn(action: StepAction, options: FootstepPlannerOptions) -> StepAction | None:
    """``action`` moved outward by the smallest multiple of :data:`CLEARANCE_STEP` that makes
    it kinematically valid, or None when no shift up to ``max_side_step`` does.

    A turn rotates the swing sole about its centre.  Turning by tau brings one
    inner corner, at (+-l, -w) in the sole's frame (l, w the half length and
    width grown by foot_margin), closer to the support sole by about
    ``l |sin tau| - w (1 - cos tau)``: toe-out swings the heel in, toe-in the
    toe.  With the soles close together (TALOS: 0.17 m apart, 0.13 m wide,
    a 0.02 m margin leaves 0.02 m) a full turn in place then overlaps the
    support sole, and without the shift the only valid turns in place were
    half turns: a quarter turn took ten steps where five suffice.
    """
    outward = action.outward
    while outward <= action.outward + options.max_side_step + 1e-12:
        shifted = StepAction(action.forward, outward, action.turn)
        if is_kinematically_valid(shifted, options):
            return shifted
        outward += CLEARANCE_STEP
    return None


def is_kinematically_valid(action: StepAction, options: FootstepPlannerOptions) -> bool:
    """Within the step limits, on the swing foot's own side, soles apart.

    Checked for a left swing foot (the right one mirrors it): forward offset
    in [-max_backward_step, max_stride], lateral offset in
    [min_foot_separation, nominal + max_side_step] (so the legs never cross),
    |turn| <= max_turn, and the soles, the swing one grown by foot_margin,
    do not overlap.
    """
    return _left_swing_is_valid(*action.swing_offset(Foot.LEFT, options.nominal_foot_separation), options)


def is_reachable_step(support: Footstep, swing: Footstep, options: FootstepPlannerOptions) -> bool:
    """Can ``swing`` be placed from ``support`` (the other foot)? The same limits as
    :func:`is_kinematically_valid`, for an arbitrary placement: the swing pose in the
    support sole's frame, mirrored for a right swing foot."""
    dx, dy = swing.x - support.x, swing.y - support.y
    cos_yaw, sin_yaw = math.cos(support.yaw), math.sin(support.yaw)
    x, y = cos_yaw * dx + sin_yaw * dy, -sin_yaw * dx + cos_yaw * dy
    yaw = math.remainder(swing.yaw - support.yaw, math.tau)
    sign = swing.foot.sign
    return _left_swing_is_valid(x, sign * y, sign * yaw, options)


def _left_swing_is_valid(x: float, y: float, yaw: float, options: FootstepPlannerOptions) -> bool:
    """A left swing foot at (x, y, yaw) in the support sole's frame: within the step limits
    (1e-9 of rounding allowed) and clear of the support sole."""
    tolerance = 1e-9
    within = (-options.max_backward_step - tolerance <= x <= options.max_stride + tolerance
              and options.min_foot_separation - tolerance <= y <= options.max_stance_separation + tolerance
              and abs(yaw) <= options.max_turn + tolerance)
    return within and not _soles_overlap(x, y, yaw, options)


def _soles_overlap(x: float, y: float, yaw: float, options: FootstepPlannerOptions) -> bool:
    """Does the swing sole at (x, y, yaw), grown by foot_margin, touch the support sole at 0?"""
    support = PackedPolygons.pack([rectangle_corners(
        np.zeros(1), np.zeros(1), np.zeros(1), options.foot_length / 2.0,
        options.foot_width / 2.0)[0]])
    half = np.array([[options.foot_length / 2.0 + options.foot_margin,
                      options.foot_width / 2.0 + options.foot_margin]])
    return bool(rectangles_overlap_polygons(np.array([[x, y]]), rectangle_axes(np.array([yaw])),
                                            half, support)[0, 0])


@dataclass(frozen=True, eq=False)
class ActionTable:
    """The actions of one swing foot as arrays in the support foot's frame, for batch expansion.

    Attributes:
        swing_foot: the foot these actions move.
        foot: (K, 3) swing-foot pose (x, y, yaw).
        centre: (K, 2) new stance centre c(F') (its yaw is ``foot[:, 2]``).
        midpoint: (K, 3) body pose of the double stance (F, F'): the soles' midpoint and mean yaw.
        support_centre: (2,) c(F), the stance centre of the support foot.
        cost: (K,) step costs; ``step_costs`` holds the same as floats for the search loop.
        points: (3K + 1, 2) the foot, centre and midpoint positions stacked,
            then c(F): one matrix product rotates them all into the world.
    """

    swing_foot: Foot
    foot: FloatArray
    centre: FloatArray
    midpoint: FloatArray
    support_centre: FloatArray
    cost: FloatArray
    step_costs: tuple[float, ...]
    points: FloatArray

    @classmethod
    def build(cls, actions: tuple[StepAction, ...], swing_foot: Foot,
              options: FootstepPlannerOptions) -> ActionTable:
        """Tabulate ``actions`` for ``swing_foot``."""
        separation = options.nominal_foot_separation
        foot = np.array([a.swing_offset(swing_foot, separation) for a in actions])
        centre = np.array([a.centre_offset(swing_foot, separation) for a in actions])
        midpoint = np.column_stack((foot[:, :2] / 2.0, foot[:, 2] / 2.0))
        support_centre = np.array([0.0, swing_foot.sign * separation / 2.0])
        cost = np.array([a.cost(options) for a in actions])
        points = np.vstack((foot[:, :2], centre, midpoint[:, :2], support_centre[None]))
        return cls(swing_foot, foot, centre, midpoint, support_centre, cost,
                   tuple(cost.tolist()), points)


@dataclass(frozen=True, eq=False)
class ActionSet:
    """The planner's actions, tabulated per swing foot, with the bounds its maths needs.

    Attributes:
        actions: the canonical actions (left swing foot).
        tables: one :class:`ActionTable` per swing foot.
        max_centre_shift: D, the largest centre move of one step (m).
        max_turn: A, the largest yaw change of one step (rad).
        max_body_hop: the largest distance between consecutive checked body
            centres, c(F) -> midpoint(F, F') -> c(F') (m).
        body_reach: distance from c(F) beyond which nothing checked during one
            expansion can reach, including soles and body grown by their margins (m).
    """

    actions: tuple[StepAction, ...]
    tables: Mapping[Foot, ActionTable]
    max_centre_shift: float
    max_turn: float
    max_body_hop: float
    body_reach: float

    @property
    def step_effects(self) -> Mapping[Foot, StepEffects]:
        """Per swing foot, how its actions move the stance centre (support frame) and turn."""
        return MappingProxyType({foot: StepEffects(table.centre - table.support_centre, table.foot[:, 2])
                                 for foot, table in self.tables.items()})

    @classmethod
    def from_options(cls, options: FootstepPlannerOptions) -> ActionSet:
        """The candidate actions that are kinematically valid, tabulated for both feet."""
        actions = candidate_actions(options)
        tables = MappingProxyType({foot: ActionTable.build(actions, foot, options)
                                   for foot in Foot})
        table = tables[Foot.LEFT]
        hop_in = np.hypot(*(table.midpoint[:, :2] - table.support_centre).T)
        hop_out = np.hypot(*(table.centre - table.midpoint[:, :2]).T)
        foot_radius = math.hypot(options.foot_length / 2.0 + options.foot_margin,
                                 options.foot_width / 2.0 + options.foot_margin)
        body_radius = math.hypot(options.body_half_width + options.body_margin,
                                 options.body_reach_depth)
        foot_reach = np.hypot(*(table.foot[:, :2] - table.support_centre).T) + foot_radius
        centre_reach = np.hypot(*(table.centre - table.support_centre).T) + body_radius
        return cls(
            actions=actions, tables=tables,
            max_centre_shift=max(a.centre_shift for a in actions),
            max_turn=max(abs(a.turn) for a in actions),
            max_body_hop=float(max(hop_in.max(), hop_out.max())),
            body_reach=float(max(foot_reach.max(), centre_reach.max(), hop_in.max() + body_radius)),
        )
