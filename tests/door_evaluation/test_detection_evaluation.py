"""The detector's evaluations on the simulator and its benchmark run and return sane numbers
(no timing asserts)."""

from __future__ import annotations

import math

import numpy as np

from door_detection.neck import neck_of
from door_detection.options import DetectionOptions
from door_evaluation.detection import benchmark, evaluate_sim, table_two
from door_evaluation.detection.search_trial import SearchOutcome
from door_evaluation.detection.sim_scenes import Scenario, render_scenario
from door_evaluation.detection.table_two import TrialResult, failed_starts, judge
from door_evaluation.detection.trial_scenes import TrialScene
from door_robot.kinematics import RobotKinematics
from door_robot.profile import load_profile


def test_sim_evaluation_on_a_tiny_grid(capsys) -> None:
    grid = evaluate_sim.EvaluationGrid(distances=(2.0,), yaws=(0.0,), noises=(0.0,))
    outcomes = evaluate_sim.run_evaluation(grid, DetectionOptions(), progress=False)
    assert len(outcomes) == 1
    assert outcomes[0].automatic.success and outcomes[0].operator.success
    text = evaluate_sim.report(outcomes, grid)
    assert "2.0 m |" in text and "1/1" in text and "Table II" in text


def test_benchmark_report() -> None:
    straight_on = render_scenario(Scenario(distance=2.0, yaw=0.0))
    automatic, operator = benchmark.benchmark_scene(straight_on, DetectionOptions(), repeats=2)
    assert automatic.success and operator.success and len(automatic.seconds) == 2
    text = benchmark.report([(automatic, operator)])
    assert "paper   2050 ms/frame" in text and "faster" in text


def test_table_two_with_the_head_search_on_one_cell() -> None:
    grid = table_two.TableTwoGrid(distances=(3.0,), yaws=(0.6,), trials=1, seed=3)
    results = table_two.run_table(grid, neck_of(RobotKinematics(load_profile("talos"))), progress=False)
    assert len(results) == 1 and results[0].scenario.yaw == 0.6
    automatic = results[0].automatic
    assert automatic.success and automatic.frames >= 2 and automatic.sim_time >= 0.5
    text = table_two.report(results, grid)
    assert "TABLE II (ours" in text and "3.0 m |" in text and "[Banerjee 2015] Table II" in text
    assert "target ≥ 98% in every cell: met" in text


def test_a_search_without_a_door_is_judged_a_failure() -> None:
    result = judge(SearchOutcome(None, 12, 6, 9.0, (0.02,) * 12), np.zeros(3), np.array([-1.0, 0, 0]), 0.9)
    assert not result.success and result.outcome == "no door confirmed" and math.isnan(result.handle_error)
    assert (result.frames, result.views) == (12, 6)
    listed = failed_starts([TrialResult(TrialScene(2.0, 0.4, seed=7), result, result)], "automatic")
    assert "no door confirmed" in listed and "TrialScene(distance=2.0, yaw=0.4" in listed and "seed=7" in listed


def test_table_two_in_two_processes_gives_the_same_trials_in_the_same_order() -> None:
    neck = neck_of(RobotKinematics(load_profile("talos")))
    grid = table_two.TableTwoGrid(distances=(2.0,), yaws=(-0.2,), trials=2, seed=5)
    alone = table_two.run_table(grid, neck, progress=False)
    parallel = table_two.run_table(grid, neck, progress=False, jobs=2)
    assert [r.scenario for r in parallel] == [r.scenario for r in alone] == grid.scenes()
    assert [r.automatic.handle_error for r in parallel] == [r.automatic.handle_error for r in alone]
