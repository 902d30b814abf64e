"""The Monte-Carlo's sampling, resuming and printed summary, on synthetic reports (no graph)."""

import json
import os
import signal

import numpy as np
import pytest

from door_bringup.door_task import TaskOptions
from door_bringup.monte_carlo import (
    SETTINGS_FILE,
    TRIAL_FILE,
    ResumeError,
    WorkerLost,
    _run_folder,
    door_classes_line,
    draw_trials,
    falls_line,
    main,
    overhead_line,
    run_trials,
    sample_trial,
    summary,
    wall_time_line,
)
from door_bringup.table_one import format_table, phase_rows
from door_bringup.workspace import Workspace


def _report(opening: str, done: bool, detection_s: float, planning_s: float) -> dict:
    attempts = [{"state": "DETECT_DOOR", "attempt": 1, "outcome": "succeeded", "planning_s": detection_s,
                 "moving_s": 0.0, "waiting_s": 0.0, "reason": ""},
                {"state": "WALK_TO_DOOR", "attempt": 1, "outcome": "succeeded" if done else "failed",
                 "planning_s": planning_s, "moving_s": 5.0, "waiting_s": 0.0, "reason": ""}]
    return {"options": {"opening": opening, "hinge": "left"}, "final_state": "DONE" if done else "FAILED",
            "failure_reason": "" if done else "WALK_TO_DOOR: planning failed", "attempts": attempts}


def test_trials_are_reproducible_from_the_seed_and_within_their_ranges():
    draws = [sample_trial(np.random.default_rng(3), TaskOptions(), 0) for _ in range(2)]
    assert draws[0] == draws[1]
    trial = draws[0]
    assert trial.opening in ("push", "pull") and trial.hinge in ("left", "right")
    assert 2.0 <= trial.distance <= 3.5 and 0.86 <= trial.door_width <= 0.96


def test_overhead_is_the_median_of_the_runs_planning_and_detection():
    reports = [_report("push", True, 1.0, 0.5), _report("pull", True, 2.0, 1.0), _report("push", False, 3.0, 3.0)]
    line = overhead_line(reports)
    assert "median 3.00 s" in line and "min 1.50 s" in line and "max 6.00 s" in line
    assert "detection median 2.00 s" in line and line.endswith("missed")
    assert overhead_line([_report("push", True, 0.5, 0.5)]).endswith("met")
    assert "robot clock" not in line  # reports written before robot_s: no latency claimed


def test_the_detection_latency_is_the_median_of_detect_doors_robot_time():
    reports = [_report("push", True, 9.0, 0.5), _report("pull", True, 7.0, 0.5), _report("push", True, 8.0, 0.5)]
    for report, robot_s in zip(reports, (0.4, 0.9, 2.5)):
        report["attempts"][0]["robot_s"] = robot_s
    line = overhead_line(reports)
    assert "detection median 8.00 s" in line  # wall clock
    assert line.endswith("robot clock median 0.90 s (max 2.50 s), target ≤ 0.5 s missed")


def test_summary_counts_each_opening_and_names_the_failures():
    text = summary([_report("push", True, 1.0, 0.5), _report("pull", False, 1.0, 0.5)])
    assert "push doors (paper: 91 % overall)" in text and "pull doors (paper: 82 % overall)" in text
    assert "All doors: 1/2 (50 %)" in text
    assert "- trial 1: WALK_TO_DOOR: planning failed" in text


def _of_class(opening: str, hinge: str, done: bool) -> dict:
    report = _report(opening, done, 1.0, 0.5)
    report["options"]["hinge"] = hinge
    return report


def test_each_door_class_counts_alike_in_the_class_balanced_rate():
    """9 of 10 doors DONE pooled, but the class with one door failed it: 3 classes at 100 %,
    one at 0 % → 75 % class-balanced."""
    reports = ([_of_class("push", "right", True)] * 3 + [_of_class("pull", "left", True)] * 3
               + [_of_class("pull", "right", True)] * 3 + [_of_class("push", "left", False)])
    line = door_classes_line(reports)
    assert line == ("By door class: pull left 3/3, pull right 3/3, push left 0/1, push right 3/3; "
                    "class-balanced 75 % (each of the 4 classes weighted alike)")
    assert line in summary(reports)
    assert door_classes_line([]) == "By door class: no trials"


def _fell_in(state: str) -> dict:
    report = _report("push", False, 1.0, 0.5)
    report["attempts"] = [*report["attempts"][:1], {**report["attempts"][1], "outcome": "succeeded"},
                          {"state": state, "attempt": 1, "outcome": "fell", "planning_s": 0.1, "moving_s": 3.0,
                           "waiting_s": 0.0, "reason": "the robot fell: base tilted 35° (more than 34°)"}]
    return report


def test_falls_are_counted_per_phase_from_the_attempts_outcome():
    fell, fell_opening = _fell_in("WALK_THROUGH"), _fell_in("OPEN_DOOR/PUSH")
    said_fell = _report("pull", False, 1.0, 0.5)  # a reason that mentions a fall is not a fall
    said_fell["failure_reason"] = "WALK_TO_DOOR: the robot fell? no: planning failed"
    reports = [fell, fell_opening, _fell_in("WALK_THROUGH"), said_fell, _report("push", True, 1.0, 0.5)]
    assert falls_line(reports) == "Falls: 3/5 runs (OPEN_DOOR 1 (PUSH 1), WALK_THROUGH 2)"
    assert falls_line([_report("push", True, 1.0, 0.5)]) == "Falls: 0/1 runs (none)"
    pull = [_fell_in("WALK_THROUGH/TO_DOORWAY"), _fell_in("WALK_THROUGH/TO_DOORWAY"), _fell_in("WALK_THROUGH")]
    assert falls_line(pull) == "Falls: 3/3 runs (WALK_THROUGH 3 (TO_DOORWAY 2, WALK_THROUGH 1))"
    assert "Falls: 3/5" in summary(reports)


def test_table_one_counts_each_phases_falls_and_slips():
    """Table I has a falls and a slips column per phase: a fall ends its run in the phase it
    happened in; a slip sends OPEN_DOOR back to MOVE_TO_HANDLE, so one run may slip twice."""
    slipped = _report("push", True, 1.0, 0.5)
    slip = {"state": "OPEN_DOOR/TURN_HANDLE", "attempt": 1, "outcome": "slipped", "planning_s": 0.1,
            "moving_s": 2.0, "waiting_s": 0.0, "reason": "hand slipped"}
    slipped["attempts"] += [slip, {**slip, "attempt": 2}, {**slip, "attempt": 3, "outcome": "succeeded"}]
    rows = {row.phase: row for row in phase_rows([slipped, _fell_in("WALK_THROUGH"), _fell_in("WALK_THROUGH")])}
    assert (rows["OPEN_DOOR"].slips, rows["OPEN_DOOR"].falls, rows["OPEN_DOOR"].successes) == (2, 0, 1)
    assert (rows["WALK_THROUGH"].falls, rows["WALK_THROUGH"].runs, rows["WALK_THROUGH"].successes) == (2, 2, 0)
    table = format_table(list(rows.values()), 3, 1, "push doors")
    assert "| phase | success | falls | slips |" in table
    assert "| OPEN_DOOR | 1/1 (100 %) | 0 | 2 |" in table and "| WALK_THROUGH | 0/2 (0 %) | 2 | 0 |" in table
    assert "| **overall** | **1/3 (33 %)** | 2 | 2 |" in table


def test_the_wall_time_per_trial_is_its_median_and_range():
    reports = [{**_report("push", True, 1.0, 0.5), "wall_time_s": seconds} for seconds in (300.4, 120.0, 250.0)]
    assert wall_time_line(reports) == "Wall time per trial: median 250 s (min 120 s, max 300 s)"
    assert wall_time_line([_report("push", True, 1.0, 0.5)]) == "Wall time per trial: not recorded"


def test_a_resumed_run_reads_its_finished_trials_and_runs_none_again(tmp_path):
    settings = {"trials": 2, "seed": 4, "autonomy": "full", "camera_rate": 2.0, "openings": ["pull", "push"],
                "timeout": 600.0}
    (tmp_path / SETTINGS_FILE).write_text(json.dumps(settings))
    trials = draw_trials(np.random.default_rng(4), TaskOptions(), 2, ["push", "pull"])
    for index, opening in enumerate(("push", "pull")):
        folder = tmp_path / f"trial_{index:03d}"
        folder.mkdir()
        (folder / TRIAL_FILE).write_text(json.dumps(_report(opening, index == 0, 1.0, 0.5)))
    workspace = Workspace(tmp_path)  # a graph would need a built workspace: none is started
    assert _run_folder(tmp_path / "runs", tmp_path, settings) == tmp_path
    reports = run_trials(trials, tmp_path, workspace, jobs=2)
    assert [r["final_state"] for r in reports] == ["DONE", "FAILED"]


def test_a_new_campaign_gets_a_folder_of_its_own_under_the_runs_dir_with_its_settings(tmp_path):
    settings = {"trials": 3, "seed": 7}
    out = _run_folder(tmp_path / "runs", None, settings)
    assert out.parent == tmp_path / "runs" and out.name.startswith("monte_carlo_")
    assert json.loads((out / SETTINGS_FILE).read_text()) == settings


def _worker_ended_by_its_teardown_bound(options, trial_dir, workspace):
    """A worker whose operator teardown hung: the kernel's alarm ends it (door_task.OPERATOR_TEARDOWN)."""
    os.kill(os.getpid(), signal.SIGALRM)


@pytest.mark.parametrize("jobs", [1, 2])
def test_a_worker_that_dies_stops_the_campaign_with_worker_lost_not_a_hang(tmp_path, jobs):
    """Stop 38: a worker hung 90 min in its operator's teardown and the pool waited for it; the
    teardown now ends the worker, and the campaign stops, resumable, instead of waiting. With
    one job too: the trial runs in a worker, so the alarm does not end the campaign itself."""
    trials = draw_trials(np.random.default_rng(4), TaskOptions(), 2, ["push", "pull"])
    with pytest.raises(WorkerLost, match="worker died"):
        run_trials(trials, tmp_path, Workspace(tmp_path), jobs=jobs, worker=_worker_ended_by_its_teardown_bound)
    assert not list(tmp_path.glob("trial_*/trial.json"))  # nothing is counted as run: --resume runs both


def test_a_run_is_not_resumed_with_other_settings(tmp_path):
    (tmp_path / SETTINGS_FILE).write_text('{"trials": 50, "seed": 0}')
    with pytest.raises(ResumeError, match="seed"):
        _run_folder(tmp_path / "runs", tmp_path, {"trials": 50, "seed": 1})
    with pytest.raises(ResumeError, match="not a Monte-Carlo run folder"):
        _run_folder(tmp_path / "runs", tmp_path / "elsewhere", {"trials": 50, "seed": 0})


def test_a_campaign_resumed_with_more_trials_is_extended_by_the_seeds_next_doors(tmp_path):
    settings = {"trials": 3, "seed": 7, "autonomy": "full", "openings": ["pull", "push"]}
    (tmp_path / SETTINGS_FILE).write_text(json.dumps(settings))
    assert _run_folder(tmp_path / "runs", tmp_path, {**settings, "trials": 5}) == tmp_path
    assert json.loads((tmp_path / SETTINGS_FILE).read_text())["trials"] == 5  # resumed again with 5 from now on
    longer = draw_trials(np.random.default_rng(7), TaskOptions(), 5, ["push", "pull"])
    assert draw_trials(np.random.default_rng(7), TaskOptions(), 3, ["push", "pull"]) == longer[:3]
    with pytest.raises(ResumeError, match="campaign of 5 trials: resume it with --trials 5 or more, not 4"):
        _run_folder(tmp_path / "runs", tmp_path, {**settings, "trials": 4})
    with pytest.raises(ResumeError, match="seed"):
        _run_folder(tmp_path / "runs", tmp_path, {**settings, "trials": 6, "seed": 8})
    assert json.loads((tmp_path / SETTINGS_FILE).read_text())["trials"] == 5  # a refused resume writes nothing


def test_the_same_seed_draws_the_same_doors_in_the_same_order():
    first = draw_trials(np.random.default_rng(7), TaskOptions(), 5, ["pull"])
    assert first == draw_trials(np.random.default_rng(7), TaskOptions(), 5, ["pull"])
    assert {trial.opening for trial in first} == {"pull"}


@pytest.mark.parametrize("argv", [["--jobs", "0"], ["--trials", "0"]])
def test_no_trials_or_no_jobs_is_refused_before_anything_runs(argv):
    with pytest.raises(SystemExit) as stop:
        main(argv)
    assert stop.value.code == 2


def _recorded(folder, **changed) -> None:
    """A Monte-Carlo folder as ``main`` writes it with its defaults (and ``changed``)."""
    settings = {"robot": "talos", "trials": 50, "seed": 0, "autonomy": "full", "camera_rate": 2.0,
                "camera_rate_standing": 8.0, "openings": ["pull", "push"], "timeout": 600.0, "ranges": "full",
                **changed}
    (folder / SETTINGS_FILE).write_text(json.dumps(settings))


def test_a_run_is_not_resumed_with_another_robot(tmp_path, capsys):
    _recorded(tmp_path)
    with pytest.raises(SystemExit) as stop:  # refused before any trial runs (none would run here)
        main(["--robot", "g1", "--resume", str(tmp_path)])
    assert stop.value.code == 2
    assert 'other settings (robot): {"robot": "talos"}' in capsys.readouterr().err
    assert not list(tmp_path.glob("trial_*"))


def test_a_runs_dir_that_is_a_file_is_refused_in_one_line(tmp_path, capsys):
    not_a_folder = tmp_path / "runs"
    not_a_folder.write_text("")
    with pytest.raises(SystemExit) as stop:
        main(["--trials", "1", "--runs-dir", str(not_a_folder)])
    assert stop.value.code == 2
    said = capsys.readouterr().err
    assert "--runs-dir: cannot make the campaign's folder" in said and "Traceback" not in said


def test_a_folder_from_before_the_robot_option_resumes_as_talos_only(tmp_path):
    settings = {"trials": 2, "seed": 4}
    (tmp_path / SETTINGS_FILE).write_text(json.dumps(settings))  # no "robot": written before --robot
    assert _run_folder(tmp_path / "runs", tmp_path, {**settings, "robot": "talos"}) == tmp_path
    with pytest.raises(ResumeError, match=r"\(robot\)"):
        _run_folder(tmp_path / "runs", tmp_path, {**settings, "robot": "g1"})


def test_the_robot_is_in_the_settings_and_in_every_trial(tmp_path):
    out = _run_folder(tmp_path / "runs", None, {"robot": "g1", "trials": 1})
    assert json.loads((out / SETTINGS_FILE).read_text())["robot"] == "g1"
    trials = draw_trials(np.random.default_rng(1), TaskOptions(robot="g1"), 3, ["push", "pull"])
    assert {trial.robot for trial in trials} == {"g1"}


def test_a_folder_from_before_the_standing_camera_rate_resumes_only_with_the_one_rate(tmp_path):
    _recorded(tmp_path)
    settings = json.loads((tmp_path / SETTINGS_FILE).read_text())
    del settings["camera_rate_standing"]  # written before it: the camera ran at camera_rate throughout
    (tmp_path / SETTINGS_FILE).write_text(json.dumps(settings))
    assert _run_folder(tmp_path / "runs", tmp_path, {**settings, "camera_rate_standing": 0.0}) == tmp_path
    with pytest.raises(ResumeError, match=r"\(camera_rate_standing\)"):
        _run_folder(tmp_path / "runs", tmp_path, {**settings, "camera_rate_standing": 8.0})


def test_the_camera_rates_reach_the_sim_bridge():
    overrides = TaskOptions(camera_rate=2.0, camera_rate_standing=6.0).node_overrides()["sim_bridge"]
    assert "camera_rate:=2.0" in overrides and "camera_rate_standing:=6.0" in overrides
