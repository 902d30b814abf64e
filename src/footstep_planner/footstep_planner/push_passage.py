"""A push door passed sideways, the back to the hinge, the leading shoulder first (the default).

TALOS's shoulders are 0.76 m across (0.80 m with the grippers) in a 0.87 m clear opening.
Walking through facing the doorway, the hinge-side shoulder passes 4 cm from the hinge
post, so the leaf must be pushed open to ~1.53 rad, and near its axis: the shoulder wedged
the leaf with 100-180 N sideways and 20 of 27 push doors fell there (issue #11). Sideways
the body is 0.50 m deep, and the leaf only has to clear the robot's back, ~0.36 m from the
hinge: 1.17 rad, pushed at the handle, 0.84 m from the axis. Turning sideways after the
door is opened takes 5+ steps, and meanwhile the closer shuts and latches the door; so the
robot already stands sideways to open it, as a person carrying a box backs through:

* :func:`~footstep_planner.goals.push_stand_pose`: ``reach`` m in front of the door plane,
  ``offset`` m from the opening's centre towards the latch, facing along the wall towards the
  latch. The door is on the side of the robot's hinge-side hand, which opens it with the torso
  turned ~80° towards it (the motion library's approach, turn and push as when facing), then
  stays on the leaf with its arm inside the doorway (``ready_to_walk``, which tells the stances
  apart by the door's direction in the base frame);
* :func:`push_passage_legs`: side-step through along that line, the hand and then the back
  (the handle resting on it, 10-20 N) pushing the leaf open, to ``beyond`` m past the door
  plane; step forward ``away`` m, away from the hinge, out of the closing leaf's sweep (side-
  stepping on, the body sways 5-7 cm back at every step and the handle hooks the pelvis as
  the back's corner passes it: 200-300 N); turn to face away.

The leaf is no obstacle of these legs (the robot pushes it); wall and posts are.

**The default** (``push_passage: sideways``; ``facing`` is
:func:`~footstep_planner.narrow.passage_legs` around the leaf at ``passage_door_angle``). The
passage rig, placed at the stand pose (10 jittered trials per hinge): 12 of 20 doors through
with a perfect estimate, against 0 of 20 facing (issue #11). With the estimate off as the
detector's is (``--estimate-error 0.6 0.5``: up to 6 mm per axis and 0.5°) and the compliant
grasp, facing opened 13 of 13 doors and fell in every passage; sideways went through 3 of 10
(left hinge). The rigid grasp had made the sideways opening fail with such errors (the hand
reaches the handle near full stretch; the turn slipped in 2 of 2 graph runs); with the
compliant one the graph opened both doors tried and passed one (push, right hinge, seed 3).
What still falls: side-stepping sways the body ±10 cm along the walk, so the hand on the leaf
bangs it (200-700 N) while the leaf is below ~0.9 rad, and a shoulder or thigh strikes the frame.

**A wide door in two walks around a tuck** (:class:`DoorwayCut`, stop 45). The arm opens
the door only to ~0.20 rad from the sideways stance, so the walk pushes the leaf on with the
hand, whose contact slides from ~0.5 m to the free edge over the first side-steps; through a
door ≥ 0.91 m wide it slid off the edge during a single support and the robot rolled and fell
(3 of 6 walks of a 0.95 m door). So a door at least ``push_tuck_min_width`` wide is walked as a
pull door is: :attr:`~door_contract.vocabulary.WalkGoal.DOORWAY` walks the passage's plan up to
just past the door plane (``push_tuck_at``; the hand ~0.15 m from the edge, the leaf at
~1.0-1.2 rad), the pushing arm tucks to the walking posture on two feet (the leaf closes onto
the back), and
:attr:`~door_contract.vocabulary.WalkGoal.THROUGH` walks on from where it stands. On the passage
rig (walked from 2.5 m, the detector's error) doors of 0.91-0.95 m went through 17 of 18 times
so, against 9 of 18; narrower ones 10 of 12 against 12 of 12 (the leaf, released nearer its
axis, closes onto the torso): they have no doorway walk (:func:`tucks_before_passing`). The
doorway walk is the whole passage's plan cut short, not a plan to a pose at the plane: such a
plan ends in short steps that turn the feet back square to the line, under the pushing hand
(a 0.95 m door: 4 of 6 walks through so, 5 of 6 cut; the build's rig figures are in the README).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from enum import Enum

from door_contract.vocabulary import Foot
from footstep_planner.door import DoorGeometry
from footstep_planner.footstep import Pose2D
from footstep_planner.goals import push_line, towards_latch
from footstep_planner.legs import Leg
from footstep_planner.narrow import SIDEWAYS
from footstep_planner.options import FootstepPlannerOptions
from footstep_planner.plan import FootstepPlan
from footstep_planner.validation import FieldRange, check_range

__all__ = ["PUSH_LEG_NAMES", "DoorwayCut", "PushPassage", "push_passage_legs", "tucks_before_passing"]


class PushPassage(Enum):
    """How the robot passes a push door."""

    FACING = "facing"
    """Face the door to open it, walk through facing the doorway, the body pushing the leaf."""
    SIDEWAYS = "sideways"
    """Open it standing sideways beside the doorway, its back to the hinge; side-step through."""

PUSH_LEG_NAMES = ("side-step through the doorway", "step away from the leaf", "turn to face away")
"""The legs of :func:`push_passage_legs`, in order."""


def push_passage_legs(door: DoorGeometry, options: FootstepPlannerOptions, offset: float, beyond: float,
                      away: float, distance_beyond: float) -> tuple[Leg, ...]:
    """The legs through a push door from :func:`~footstep_planner.goals.push_stand_pose` (same
    ``offset``): side-step along its line (:func:`~footstep_planner.goals.push_line`) to s = −``beyond`` (each state within 0.1 rad of sideways and
    5 cm of the line: :data:`~footstep_planner.narrow.SIDEWAYS`), step ``away`` m towards the
    latch (forward) and on to ``distance_beyond`` past the plane when that is further, and
    turn there to face away from the approach side."""
    check_range("beyond", beyond, FieldRange(0.0, 5.0, "m", low_open=True))
    check_range("away", away, FieldRange(0.0, 3.0, "m"))
    check_range("distance_beyond", distance_beyond, FieldRange(0.0, 10.0, "m", low_open=True))
    line = push_line(door, options, offset)
    sideways = towards_latch(door)
    through_x, through_y = door.to_world(line, -beyond)
    away_x, away_y = door.to_world(line + away, -max(beyond, distance_beyond))
    through, aside, turned = PUSH_LEG_NAMES
    return (Leg(Pose2D(through_x, through_y, sideways), through, SIDEWAYS),
            Leg(Pose2D(away_x, away_y, sideways), aside),
            Leg(Pose2D(away_x, away_y, door.facing_yaw), turned))


def tucks_before_passing(door: DoorGeometry, min_width: float) -> bool:
    """Whether the pushing arm tucks in the doorway of ``door``: its leaf is at least
    ``min_width`` (m) wide (the module's docstring says why only then)."""
    return door.leaf_width >= min_width


@dataclass(frozen=True)
class DoorwayCut:
    """Where a wide push door's doorway walk stops in the passage's plan: at its first stance
    whose centre is at most ``at`` m before the door plane (negative: past it) and that ends an
    even number of ``/footstep_plan`` steps — the walk on then starts with the left foot, as
    every walk does, and the feet alternate across the two walks as in the one plan. The
    eligible stances are ~0.12 m apart: the rig prototype stopped after 10 steps, ~0.10 m past
    the plane (``at`` = −0.05 picks that one); stopped after 8, ~0.02 m before it, one of six
    walks of a 0.95 m door ended on a 5.2 cm landing error that the 10-step cut does not make."""

    door: DoorGeometry
    at: float

    def __post_init__(self) -> None:
        check_range("at", self.at, FieldRange(-0.5, 0.5, "m"))

    def cut(self, plan: FootstepPlan) -> FootstepPlan:
        """``plan`` up to that stance (the whole plan when none qualifies)."""
        in_place = 1 if plan.steps and plan.steps[0].foot is Foot.RIGHT else 0  # the bus's first step
        for count, stance in enumerate(plan.stances(), start=1):
            body = stance.body_pose
            if (count + in_place) % 2 == 0 and self.door.to_door(body.x, body.y)[1] <= self.at:
                return replace(plan, goal=body, steps=plan.steps[:count])
        return plan
