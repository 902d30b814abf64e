"""The quick unreachability proof: sound (never rejects a reachable goal) and useful."""

from __future__ import annotations

import math

import numpy as np
from footstep_scenes import door_facing_robot

from door_contract.vocabulary import DoorOpening
from footstep_planner.geometry import Bounds
from footstep_planner.reachability import ReachabilityQuery, flood_fill, may_reach
from footstep_planner.world import World


def _query(goal: tuple[float, float], hop: float = 0.15) -> ReachabilityQuery:
    return ReachabilityQuery(bounds=Bounds(-1.0, 5.0, -2.5, 2.5), seeds=((0.5, 0.0),), goal=goal,
                             goal_radius=0.05, body_radius=0.17, hop=hop)


def test_flood_fill_follows_4_connected_free_cells() -> None:
    free = np.array([[1, 1, 0, 1],
                     [0, 1, 0, 1],
                     [1, 1, 0, 1],
                     [1, 0, 1, 1]], dtype=bool)
    seeds = np.zeros_like(free)
    seeds[0, 0] = True
    reached = flood_fill(free, seeds)
    assert reached.tolist() == [[1, 1, 0, 0], [0, 1, 0, 0], [1, 1, 0, 0], [1, 0, 0, 0]]


def test_flood_fill_does_not_leak_diagonally() -> None:
    free = np.array([[1, 0], [0, 1]], dtype=bool)
    seeds = np.array([[1, 0], [0, 0]], dtype=bool)
    assert flood_fill(free, seeds).sum() == 1


def test_closed_door_is_proved_unreachable_and_open_door_is_not() -> None:
    door = door_facing_robot(DoorOpening.PUSH, angle=0.0)
    goal = (3.0, 0.0)
    assert not may_reach(World.from_door(door), _query(goal))
    assert may_reach(World.from_door(door.with_angle(math.pi / 2.0)), _query(goal))


def test_partly_open_door_is_not_rejected() -> None:
    """A door open 30 degrees leaves a gap too narrow to prove anything: say "maybe"."""
    door = door_facing_robot(DoorOpening.PULL, angle=math.radians(30.0))
    assert may_reach(World.from_door(door), _query((3.0, 0.0)))


def test_nothing_is_proved_when_the_body_hops_further_than_its_size() -> None:
    door = door_facing_robot(DoorOpening.PUSH, angle=0.0)
    assert may_reach(World.from_door(door), _query((3.0, 0.0), hop=0.5))


def test_goal_in_open_space_is_reachable() -> None:
    assert may_reach(World(), _query((4.0, 2.0)))
