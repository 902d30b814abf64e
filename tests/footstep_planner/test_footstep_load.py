"""Success does not depend on CPU load (issue #13): a pull passage planned while busy-loop
processes compete for the cores gives exactly the plan it gives on a quiet machine. The
searches stop on their deterministic expansion budget; the wall clock is only a safety net."""

from __future__ import annotations

import os
import subprocess
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager

import pytest
from footstep_scenes import door_facing_robot, profile_options

from door_contract.vocabulary import DoorOpening, HingeSide, WalkGoal
from footstep_planner.astar import FootstepPlanner
from footstep_planner.footstep import Pose2D, Stance
from footstep_planner.legs import plan_legs
from footstep_planner.plan import PlanResult
from footstep_planner.requests import GoalSettings, options_for_problem, walk_problem

BUSY_LOOPS = 2 * (os.cpu_count() or 2)
"""Busy processes beside the planner: two per core."""


def _cpu_seconds(pid: int) -> float:
    """User + system CPU time of a process so far (s), from /proc."""
    with open(f"/proc/{pid}/stat") as stat:
        fields = stat.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


@contextmanager
def busy_cpu(count: int) -> Iterator[list[subprocess.Popen]]:
    """``count`` processes spinning in a loop, each already burning CPU when the body runs;
    killed (by their own pids) afterwards."""
    loops = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(count)]
    try:
        deadline = time.monotonic() + 30.0
        while not all(_cpu_seconds(loop.pid) > 0.05 for loop in loops):
            assert time.monotonic() < deadline, "the busy loops never started"
            time.sleep(0.01)
        yield loops
    finally:
        for loop in loops:
            loop.kill()
        for loop in loops:
            loop.wait(timeout=10)


def _pull_passage(width: float, hinge: HingeSide) -> PlanResult:
    """The node's pull passage for a door of this width, from the stand pose."""
    options = profile_options()
    door = door_facing_robot(DoorOpening.PULL, hinge_side=hinge, leaf_width=width, clear_opening=width,
                             handle_offset=0.07, angle=0.35)
    settings = GoalSettings()
    stand = walk_problem(WalkGoal.STAND, door, Stance.nominal(Pose2D(-1.0, 0.0, 0.0), 0.2), options,
                         settings).legs[0].goal
    problem = walk_problem(WalkGoal.THROUGH, door, Stance.nominal(stand, options.nominal_foot_separation),
                           options, settings)
    planner = FootstepPlanner(problem.world, options_for_problem(problem, WalkGoal.THROUGH, options))
    return plan_legs(planner, problem.start, problem.legs)


@pytest.mark.parametrize(("width", "hinge"), [(0.99, HingeSide.LEFT), (0.80, HingeSide.RIGHT)])
def test_a_pull_passage_plans_the_same_with_the_cpu_busy(width: float, hinge: HingeSide) -> None:
    quiet = _pull_passage(width, hinge)
    assert quiet.succeeded, quiet.reason
    with busy_cpu(BUSY_LOOPS) as loops:
        loaded = [_pull_passage(width, hinge) for _ in range(3)]
        assert all(loop.poll() is None for loop in loops)  # still spinning throughout
    for result in loaded:
        assert result.succeeded, result.reason
        assert result.expansions == quiet.expansions
        assert result.plan.steps == quiet.plan.steps
