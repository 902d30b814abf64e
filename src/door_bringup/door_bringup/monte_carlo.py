"""``door_monte_carlo``: the door task over randomised doors, as [Banerjee 2015]'s Table I.

    python -m door_bringup.monte_carlo --trials 50 [--robot g1] [--seed 0] [--autonomy full] [--jobs 2] [--ranges full|narrow]
    python -m door_bringup.monte_carlo --trials 50 --resume runs/monte_carlo_<stamp>
    python -m door_bringup.monte_carlo --trials 100 --resume runs/monte_carlo_<stamp>   # extend it

Each trial runs the whole graph (separate processes, real DDS) on a door drawn from the
seed: push or pull, left or right hinge, start distance, lateral offset and yaw, door
width, handle height, wind on the door, depth noise and (``--ranges full``, the default) the
scene's colours, within issue #13's full ranges or the earlier narrow ones
(:mod:`door_bringup.trial_ranges`). Prints a progress bar, then
success rates per phase and overall, and writes ``runs/monte_carlo_<stamp>/summary.md``. Every
finished trial is kept in ``trial_<n>/trial.json``: ``--resume`` reads those and runs the rest
(the doors come from the seed, so the same settings draw the same doors). The settings,
the robot among them, are kept in ``monte_carlo.json``: a folder is resumed only with the
settings it was started with, but for ``--trials``, which may grow: a 50-door campaign resumed
with ``--trials 100`` runs the seed's next 50 doors (a seed draws its doors in order).
"""

from __future__ import annotations

import argparse
import json
import multiprocessing
import os
import signal
import statistics
import sys
import time
from collections import Counter
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor, as_completed
from concurrent.futures.process import BrokenProcessPool
from dataclasses import asdict
from datetime import UTC, datetime
from pathlib import Path

import numpy as np

from door_bringup.domains import lease_domain
from door_bringup.door_task import TaskOptions, add_camera_arguments, run_task
from door_bringup.interrupts import INTERRUPTED, interrupt_on_sigterm
from door_bringup.robot_option import add_robot_argument, check_robot
from door_bringup.table_one import format_table, phase_of, phase_rows, state_attempts
from door_bringup.trial_ranges import NARROW, RangeSet, TrialRanges, ranges_named
from door_bringup.workspace import Workspace, repository_root
from door_contract.payloads import StateAttempt
from door_contract.vocabulary import AttemptOutcome, TaskEnd, TaskState

__all__ = ["RECORDED_BEFORE", "SETTINGS_FILE", "TRIAL_FILE", "ResumeError", "WorkerLost", "door_classes_line", "draw_trials",
           "falls_line", "main", "overhead_line", "run_trials", "sample_trial", "summary", "wall_time_line"]


def sample_trial(rng: np.random.Generator, base: TaskOptions, trial: int,
                 ranges: TrialRanges = NARROW) -> TaskOptions:
    """One randomised door drawn from ``ranges`` (:mod:`door_bringup.trial_ranges`)."""
    return ranges.draw(rng, base)


def progress(done: int, total: int, successes: int, started: float) -> str:
    width = 30
    filled = int(width * done / total)
    elapsed = time.monotonic() - started
    eta = elapsed / done * (total - done) if done else 0.0
    return (f"\r[{'#' * filled}{'.' * (width - filled)}] {done}/{total} trials, "
            f"{successes} succeeded, {elapsed:.0f} s elapsed, ~{eta:.0f} s left")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_robot_argument(parser)
    parser.add_argument("--trials", type=int, default=50)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--autonomy", choices=("full", "supervised", "step"), default="full")
    add_camera_arguments(parser)
    parser.add_argument("--openings", nargs="+", choices=("push", "pull"), default=["push", "pull"])
    parser.add_argument("--timeout", type=float, default=600.0,
                        help="per trial, s of the robot's time (sim time; 5x that of wall time as a safety net)")
    parser.add_argument("--jobs", type=int, default=1,
                        help="trials at once, each graph in a ROS domain of its own (mind the cores: a loaded "
                             "machine slows the graph, not the result)")
    parser.add_argument("--ranges", choices=[r.value for r in RangeSet], default=RangeSet.FULL.value,
                        help="full: issue #13's (start 1-4 m, +-0.6 m, +-0.6 rad; doors 0.80-1.00 m, lever "
                             "0.85-1.10 m, wind <= 3 N m, depth noise <= 0.005, random colours); narrow: the "
                             "earlier campaigns' (door_bringup.trial_ranges)")
    parser.add_argument("--runs-dir", type=Path, metavar="DIR", default=None,
                        help="where a new campaign's folder monte_carlo_<stamp> is made (default: the checkout's runs/)")
    parser.add_argument("--resume", type=Path, metavar="RUN_DIR",
                        help="a monte_carlo_<stamp> folder: its finished trials are read, the rest run")
    args = parser.parse_args(argv)
    if args.trials < 1 or args.jobs < 1:
        parser.error("--trials and --jobs must be at least 1")
    check_robot(parser, args.robot)
    interrupt_on_sigterm()
    workspace = Workspace(repository_root())
    settings = {"robot": args.robot, "trials": args.trials, "seed": args.seed, "autonomy": args.autonomy,
                "camera_rate": args.camera_rate, "camera_rate_standing": args.camera_rate_standing, "openings": sorted(args.openings), "timeout": args.timeout,
                "ranges": args.ranges}
    try:
        out = _run_folder(args.runs_dir or workspace.root / "runs", args.resume, settings)
    except ResumeError as error:
        parser.error(str(error))
    except OSError as error:  # --runs-dir names a file, or a folder that cannot be written
        parser.error(f"--runs-dir: cannot make the campaign's folder: {error}")
    base = TaskOptions(robot=args.robot, autonomy=args.autonomy, timeout_s=args.timeout, record=False,
                       camera_rate=args.camera_rate, camera_rate_standing=args.camera_rate_standing)
    trials = draw_trials(np.random.default_rng(args.seed), base, args.trials, args.openings,
                         ranges_named(RangeSet(args.ranges)))
    try:
        reports = run_trials(trials, out, workspace, args.jobs)
    except KeyboardInterrupt as signal_name:  # every graph is stopped; finished trials are on disk
        _say_stopped(f"interrupted ({signal_name or 'SIGINT'})", out, len(trials))
        return INTERRUPTED
    except WorkerLost as error:
        _say_stopped(str(error), out, len(trials))
        return 1
    text = f"Robot: {args.robot}\n\n" + summary(reports)
    print(text)
    (out / "summary.md").write_text(text)
    (out / "trials.json").write_text(json.dumps(reports, indent=2, default=str))
    return 0


def draw_trials(rng: np.random.Generator, base: TaskOptions, count: int, openings: list[str],
                ranges: TrialRanges = NARROW) -> list[TaskOptions]:
    """The seed's doors from ``ranges``, in order (redrawn until the opening is one of ``openings``)."""
    trials = []
    for trial in range(count):
        options = sample_trial(rng, base, trial, ranges)
        while options.opening not in openings:
            options = sample_trial(rng, base, trial, ranges)
        trials.append(options)
    return trials


def _run_folder(runs_dir: Path, resume: Path | None, settings: dict) -> Path:
    """A new ``<runs_dir>/monte_carlo_<stamp>``, or the folder to resume: the same settings but
    ``trials``, which may grow (the campaign is extended: a seed draws its doors in order, so
    its first doors are the ones already run); else ResumeError."""
    if resume is None:
        out = runs_dir / f"monte_carlo_{datetime.now(UTC).strftime('%Y%m%dT%H%M%SZ')}"
        out.mkdir(parents=True, exist_ok=True)
        (out / SETTINGS_FILE).write_text(json.dumps(settings, indent=2))
        return out
    recorded = resume / SETTINGS_FILE
    if not recorded.is_file():
        raise ResumeError(f"{resume} is not a Monte-Carlo run folder (no {SETTINGS_FILE})")
    stored = json.loads(recorded.read_text())
    earlier, settings = {**RECORDED_BEFORE, **stored}, {**RECORDED_BEFORE, **settings}
    differing = sorted(key for key in earlier.keys() | settings.keys()
                       if key != "trials" and earlier.get(key) != settings.get(key))
    if differing:
        raise ResumeError(f"{resume} was run with other settings ({', '.join(differing)}): "
                         f"{json.dumps({key: earlier.get(key) for key in differing})}")
    if settings["trials"] < earlier["trials"]:
        raise ResumeError(f"{resume} is a campaign of {earlier['trials']} trials: resume it with "
                         f"--trials {earlier['trials']} or more, not {settings['trials']}")
    if settings["trials"] > earlier["trials"]:  # extended: the seed's first doors are the ones run
        recorded.write_text(json.dumps({**stored, "trials": settings["trials"]}, indent=2))
    return resume


class ResumeError(Exception):
    """A folder that cannot be resumed with these settings."""


class WorkerLost(Exception):
    """A pool worker ended without returning its trial: killed, or ended by its own teardown
    bound (:data:`door_bringup.door_task.OPERATOR_TEARDOWN`: a Fast DDS deadlock destroying the
    scripted operator); the pool is broken, its other trials are stopped."""


def _say_stopped(why: str, out: Path, trials: int) -> None:
    """One line on stderr: why the campaign stopped, how far it got, how to go on."""
    finished = sum(1 for _ in out.glob(f"trial_*/{TRIAL_FILE}"))
    print(f"\n{why}: {finished} of {trials} trials finished; --resume {out} runs the rest", file=sys.stderr)


SETTINGS_FILE = "monte_carlo.json"
RECORDED_BEFORE = {"robot": "talos", "ranges": RangeSet.NARROW.value, "camera_rate_standing": 0.0}
"""What a setting a folder does not record was: folders written before ``--robot`` ran TALOS,
before ``--ranges`` the narrow ranges, before ``--camera-rate-standing`` the camera's one rate
throughout (the sim bridge's 0: resumed with ``--camera-rate-standing 0``)."""
TRIAL_FILE = "trial.json"


def run_trials(trials: list[TaskOptions], out: Path, workspace: Workspace, jobs: int,
               worker: Callable[[TaskOptions, Path, Workspace], dict] | None = None) -> list[dict]:
    """Every trial's report, in order: read where ``trial_<n>/trial.json`` exists, run otherwise
    (``jobs`` at a time, each in its own ROS domain, by ``worker``: default :func:`_run_in_worker`),
    with a progress bar. Raises :class:`WorkerLost` when a pool worker dies.

    Every trial runs in a pool worker, with ``jobs`` 1 too: a trial's scripted operator node
    (DDS in the main job's own process) that hangs in its teardown ends its process by the
    kernel's alarm (:data:`door_bringup.door_task.OPERATOR_TEARDOWN`); in a worker that is
    :class:`WorkerLost` and a resumable campaign, where in the campaign's own process it ended
    the campaign without a word (stop 43)."""
    reports: dict[int, dict] = {}
    for index in range(len(trials)):
        done = out / f"trial_{index:03d}" / TRIAL_FILE
        if done.is_file():
            reports[index] = json.loads(done.read_text())
    if reports:
        print(f"resuming: {len(reports)} of {len(trials)} trials already run", file=sys.stderr)
    pending = [index for index in range(len(trials)) if index not in reports]
    started = time.monotonic()

    def finished(index: int, report: dict) -> None:
        reports[index] = report
        successes = sum(r["final_state"] == TaskEnd.DONE for r in reports.values())
        print(progress(len(reports), len(trials), successes, started), end="", file=sys.stderr, flush=True)

    first = int(os.environ.get("ROS_DOMAIN_ID", "0") or 0) + 1  # the campaign's own stays free
    with ProcessPoolExecutor(jobs, mp_context=multiprocessing.get_context("spawn"),
                             initializer=_take_domain, initargs=(first,)) as pool:
        futures = {pool.submit(worker or _run_in_worker, trials[index], out / f"trial_{index:03d}", workspace): index
                   for index in pending}
        try:
            for future in as_completed(futures):
                finished(futures[future], future.result())
        except KeyboardInterrupt:  # Ctrl-C or SIGTERM: each worker stops its graph, no trial is started
            _stop_workers(pool)
            raise
        except BrokenProcessPool:
            _stop_workers(pool)
            raise WorkerLost("a Monte-Carlo worker died (killed, or its operator node's teardown hung: its stacks are above)") from None
    print(file=sys.stderr)
    return [reports[index] for index in range(len(trials))]


def _stop_workers(pool: ProcessPoolExecutor) -> None:
    """No trial is started any more; each running worker stops its graph (SIGTERM)."""
    pool.shutdown(wait=False, cancel_futures=True)
    for child in multiprocessing.active_children():
        if child.pid is not None:
            os.kill(child.pid, signal.SIGTERM)


def _take_domain(first: int) -> None:
    """A pool worker's ROS domain, for good: the first id from ``first`` that no process on the
    host has leased (:func:`door_bringup.domains.lease_domain`; the lease lasts as long as the
    worker), so its graphs never share DDS with another worker's, another campaign's or a main
    job's that leased one. A SIGTERM stops the worker's graph (:mod:`door_bringup.interrupts`)."""
    os.environ["ROS_DOMAIN_ID"] = str(lease_domain(first).domain)
    interrupt_on_sigterm()


def _run_in_worker(options: TaskOptions, trial_dir: Path, workspace: Workspace) -> dict:
    """:func:`run_trial` in a pool worker: interrupted, the worker exits once its graph is
    stopped, instead of starting the next trial the pool had already queued for it."""
    try:
        return run_trial(options, trial_dir, workspace)
    except KeyboardInterrupt:
        os._exit(130)  # the pool's own loop would catch a raise and take the next trial


def run_trial(options: TaskOptions, trial_dir: Path, workspace: Workspace) -> dict:
    """One trial; its report (with the options) is also written to ``trial_dir/trial.json``."""
    report = {"options": asdict(options), **run_task(options, trial_dir, workspace)}
    trial_dir.mkdir(parents=True, exist_ok=True)
    (trial_dir / TRIAL_FILE).write_text(json.dumps(report, indent=2, default=str))
    return report


def summary(reports: list[dict]) -> str:
    sections = []
    for opening, paper in (("pull", "82 %"), ("push", "91 %")):
        subset = [r for r in reports if r["options"]["opening"] == opening]
        if subset:
            ok = sum(r["final_state"] == TaskEnd.DONE for r in subset)
            sections.append(format_table(phase_rows(subset), len(subset), ok,
                                         f"{opening} doors (paper: {paper} overall)"))
    ok = sum(r["final_state"] == TaskEnd.DONE for r in reports)
    failures = [f"- trial {i}: {r['failure_reason']}" for i, r in enumerate(reports) if r["final_state"] != TaskEnd.DONE]
    return "\n\n".join(sections + [f"**All doors: {ok}/{len(reports)} "
                                   f"({100.0 * ok / max(len(reports), 1):.0f} %); target ≥ 98 %**",
                                   door_classes_line(reports), overhead_line(reports), falls_line(reports),
                                   wall_time_line(reports),
                                   "Failures:\n" + ("\n".join(failures) or "- none")]) + "\n"


def door_classes_line(reports: list[dict]) -> str:
    """Success per door class (opening × hinge) and their mean, each class weighted alike. A
    seed's 50 doors are far from even across the four classes (seed 6 drew 5 push doors hinged
    left and 23 hinged right), so the pooled rate leans on whichever classes the seed favoured;
    the class-balanced rate is what a door of any class may expect."""
    classes: dict[tuple[str, str], list[bool]] = {}
    for report in reports:
        options = report["options"]
        key = (str(options["opening"]), str(options["hinge"]))
        classes.setdefault(key, []).append(report["final_state"] == TaskEnd.DONE)
    if not classes:
        return "By door class: no trials"
    rates = [sum(done) / len(done) for done in classes.values()]
    counts = ", ".join(f"{opening} {hinge} {sum(done)}/{len(done)}" for (opening, hinge), done in sorted(classes.items()))
    return (f"By door class: {counts}; class-balanced {100.0 * statistics.fmean(rates):.0f} % "
            f"(each of the {len(classes)} classes weighted alike)")


def falls_line(reports: list[dict]) -> str:
    """Runs that ended with the robot fallen, per phase and, where a phase has sub-states, per
    sub-state: the state attempt whose outcome is ``fell`` (the FSM records it so when the
    execution reports the fall)."""
    states = Counter[TaskState](attempt.state for r in reports for attempt in state_attempts(r)
                                if attempt.outcome is AttemptOutcome.FELL)
    phases = Counter[str]()
    for state, count in states.items():
        phases[phase_of(state)] += count
    counted = ", ".join(f"{phase} {count}" + _sub_states(phase, states) for phase, count in sorted(phases.items()))
    return f"Falls: {sum(phases.values())}/{len(reports)} runs ({counted or 'none'})"


def _sub_states(phase: str, states: Counter[TaskState]) -> str:
    """`` (TO_DOORWAY 10, WALK_THROUGH 2)``: a phase's falls by the sub-state they were in, if it has any."""
    within = {state.value: n for state, n in states.items() if phase_of(state) == phase}
    if len(within) == 1 and phase in within:
        return ""
    return " (" + ", ".join(f"{state} {n}" for state, n in sorted(within.items())) + ")"


def wall_time_line(reports: list[dict]) -> str:
    """Wall time per trial (the graph's start to its stop), as the campaign ran it (``--jobs``
    graphs sharing the machine's cores)."""
    times = sorted(float(r["wall_time_s"]) for r in reports if "wall_time_s" in r)
    if not times:
        return "Wall time per trial: not recorded"
    return (f"Wall time per trial: median {statistics.median(times):.0f} s (min {times[0]:.0f} s, "
            f"max {times[-1]:.0f} s)")


def overhead_line(reports: list[dict]) -> str:
    """Perception + planning per run: wall time the robot waited for the detector and the
    planners (the FSM's planning phases, without operator or moving time)."""
    runs = [attempts for attempts in map(state_attempts, reports) if attempts]
    if not runs:
        return "Perception + planning overhead: no run reached a state"
    per_run = sorted(sum(a.planning_s for a in attempts) for attempts in runs)
    detection = [sum(a.planning_s for a in attempts if a.state is TaskState.DETECT_DOOR) for attempts in runs]
    median = statistics.median(per_run)
    return (f"Perception + planning overhead per run: median {median:.2f} s (min {per_run[0]:.2f} s, "
            f"max {per_run[-1]:.2f} s; detection median {statistics.median(detection):.2f} s); "
            f"target ≤ 2 s {'met' if median <= 2.0 else 'missed'}{_detection_latency(runs)}")


def _detection_latency(runs: list[list[StateAttempt]]) -> str:
    """DETECT_DOOR on the robot clock (the attempts' ``robot_s``; reports written before it
    existed have none): what the robot waits whatever the machine's load."""
    latency = [sum(a.robot_s for a in attempts if a.state is TaskState.DETECT_DOOR) for attempts in runs]
    latency = [seconds for seconds in latency if seconds > 0]
    if not latency:
        return ""
    median = statistics.median(latency)
    return (f"; detection latency on the robot clock median {median:.2f} s (max {max(latency):.2f} s), "
            f"target ≤ 0.5 s {'met' if median <= 0.5 else 'missed'}")


if __name__ == "__main__":
    sys.exit(main())
