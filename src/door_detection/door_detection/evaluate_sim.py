"""Evaluation on rendered scenes of the simulation core, in the form of the paper's Table II.

``python -m door_detection.evaluate_sim [--quick] [--colours all] [--noise 0 0.003]``

For every (distance, viewing angle, depth noise) cell — and door/handle colours and hinge
side cycled over the cells, or all colour pairs with ``--colours all`` — a
:class:`~door_detection.sim_scenes.Scenario` is rendered by the sim core's ``DoorWorld``
(1024×544 head camera) and both detectors run on the frame:

* automatic (Sec. III-A), no prior knowledge;
* operator-aided (Sec. III-B) on a synthetic scribble (the projected lever's outline with
  ±2 px noise), given the hinge side (the operator's knowledge) and the world's up from
  the camera pose (what tf gives the node).

Success (DESIGN.md): handle within 2 cm of the ground-truth grasp point and normal within
2° of the door's.  Prints, per mode, a table of successes per distance × angle bin, the
paper-style orientation range per distance, and the time per frame (detection only).
Seed 001 Table II: automatic worked at 1.4–2.6 m over about −0.5..0.55 rad; operator-aided
from 1 to 4 m.
"""

from __future__ import annotations

import argparse
import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from door_detection.automatic import detect_automatic
from door_detection.estimate import DetectionResult, Side
from door_detection.operator_aided import detect_from_scribble
from door_detection.options import DetectionOptions
from door_detection.progress import ProgressBar
from door_detection.sim_scenes import DOOR_COLOURS, HANDLE_COLOURS, Scenario, SceneFrame, render_scenario

HANDLE_TOLERANCE = 0.02
"""Success: handle within this distance of the ground truth (m)."""
NORMAL_TOLERANCE_DEG = 2.0
"""Success: normal within this angle of the ground truth (deg)."""
PAPER_TABLE_II = (
    ("2.6 - 4 m", "-", "failure", "-0.5 to 0.6", "success"),
    ("2.41 - 2.6 m", "-0.35 to 0.55", "success", "-0.45 to 0.55", "success"),
    ("1.8 - 2.41 m", "-0.2 to 0.5", "success", "-0.35 to 0.5", "success"),
    ("1.4 - 1.8 m", "-0.5 to 0.0", "success", "-0.5 to 0.45", "success"),
    ("1 - 1.3 m", "-", "failure", "-0.2 to 0.2", "success"),
)
"""Seed 001 Table II: distance, automatic orientation range and result, operator-aided."""


@dataclass(frozen=True)
class EvaluationGrid:
    """The scenes evaluated: distances (m) × angles (rad) × depth noise (1/m), with colour
    pairs and hinge sides cycled (``all_colours``: every door × handle colour pair)."""

    distances: tuple[float, ...] = (1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0)
    yaws: tuple[float, ...] = (-0.6, -0.4, -0.2, 0.0, 0.2, 0.4, 0.6)
    noises: tuple[float, ...] = (0.0, 0.003)
    all_colours: bool = False
    seed: int = 0

    def scenarios(self) -> list[Scenario]:
        """Every scenario, in a deterministic order."""
        pairs = list(itertools.product(DOOR_COLOURS, HANDLE_COLOURS))
        out = []
        for index, (distance, yaw, noise) in enumerate(itertools.product(self.distances, self.yaws, self.noises)):
            chosen = pairs if self.all_colours else [pairs[index % len(pairs)]]
            for k, ((_, door), (_, handle)) in enumerate(chosen):
                side = Side.LEFT if (index + k) % 2 == 0 else Side.RIGHT
                out.append(Scenario(distance, yaw, door, handle, noise, side,
                                    seed=self.seed + len(out)))
        return out


@dataclass(frozen=True)
class ModeOutcome:
    """One detector on one scene: success, errors (m, deg; nan when nothing detected),
    the outcome's name and the detection time (s)."""

    success: bool
    handle_error: float
    normal_error: float
    outcome: str
    seconds: float


@dataclass(frozen=True)
class SceneOutcome:
    scenario: Scenario
    automatic: ModeOutcome
    operator: ModeOutcome


def judge(result: DetectionResult, frame: SceneFrame) -> ModeOutcome:
    """Compare a detection with the scene's ground truth."""
    if not result.ok or result.estimate is None:
        return ModeOutcome(False, math.nan, math.nan, result.outcome.value, result.elapsed)
    estimate = result.estimate
    handle_error = float(np.linalg.norm(estimate.handle_position - frame.handle_position))
    cosine = float(np.clip(estimate.normal @ frame.normal, -1.0, 1.0))
    normal_error = math.degrees(math.acos(cosine))
    success = handle_error <= HANDLE_TOLERANCE and normal_error <= NORMAL_TOLERANCE_DEG
    return ModeOutcome(success, handle_error, normal_error, result.outcome.value, result.elapsed)


def evaluate_scene(scenario: Scenario, options: DetectionOptions) -> SceneOutcome:
    """Render one scene and run both detectors on it."""
    frame = render_scenario(scenario)
    automatic = judge(detect_automatic(frame.rgb, frame.depth, frame.intrinsics, options), frame)
    if frame.scribble is None:
        operator = ModeOutcome(False, math.nan, math.nan, "handle_not_in_image", 0.0)
    else:
        result = detect_from_scribble(frame.rgb, frame.depth, frame.intrinsics, frame.scribble, options,
                                      scenario.hinge_side, frame.up)
        operator = judge(result, frame)
    return SceneOutcome(scenario, automatic, operator)


def run_evaluation(grid: EvaluationGrid, options: DetectionOptions | None = None,
                   progress: bool = True) -> list[SceneOutcome]:
    """Evaluate every scenario of ``grid`` (progress bar on stderr)."""
    opts = options if options is not None else DetectionOptions()
    scenarios = grid.scenarios()
    bar = ProgressBar(len(scenarios), enabled=progress)
    outcomes = []
    for scenario in scenarios:
        outcomes.append(evaluate_scene(scenario, opts))
        bar.advance(f"d={scenario.distance:.1f} m yaw={scenario.yaw:+.1f} rad")
    bar.close()
    return outcomes


def _mode(outcome: SceneOutcome, mode: str) -> ModeOutcome:
    return outcome.automatic if mode == "automatic" else outcome.operator


def success_table(outcomes: Sequence[SceneOutcome], mode: str, grid: EvaluationGrid) -> str:
    """Rows: distances; columns: angle bins (successes/scenes); then the paper-style range
    of angles where every scene succeeded and the row's success rate."""
    per_cell = max(len([o for o in outcomes if o.scenario.distance == d and o.scenario.yaw == y])
                   for d in grid.distances for y in grid.yaws)
    width = max(5, 2 * len(str(per_cell)) + 1)
    header = ("distance | " + " | ".join(f"{yaw:+.1f}".center(width) for yaw in grid.yaws) +
              " | orientation range (rad) | success")
    lines = [header, "-" * len(header)]
    for distance in grid.distances:
        cells, good = [], []
        for yaw in grid.yaws:
            cell = [_mode(o, mode) for o in outcomes
                    if o.scenario.distance == distance and o.scenario.yaw == yaw]
            wins = sum(m.success for m in cell)
            cells.append(f"{wins}/{len(cell)}".center(width))
            if cell and wins == len(cell):
                good.append(yaw)
        span = f"{min(good):+.1f} to {max(good):+.1f}" if good else "-"
        rate = _rate([_mode(o, mode) for o in outcomes if o.scenario.distance == distance])
        lines.append(f"{distance:6.1f} m | " + " | ".join(cells) + f" | {span:^23} | {rate:6.1%}")
    return "\n".join(lines)


def _rate(modes: Sequence[ModeOutcome]) -> float:
    return sum(m.success for m in modes) / max(len(modes), 1)


def summary(outcomes: Sequence[SceneOutcome], mode: str) -> str:
    """Overall success, error percentiles of detected frames, failures, time per frame."""
    modes = [_mode(o, mode) for o in outcomes]
    detected = [m for m in modes if math.isfinite(m.handle_error)]
    times = np.array([m.seconds for m in modes if m.seconds > 0]) * 1000
    failures: dict[str, int] = {}
    for m in modes:
        if not m.success:
            key = m.outcome if not math.isfinite(m.handle_error) else "outside tolerance"
            failures[key] = failures.get(key, 0) + 1
    text = [f"{mode}: success {sum(m.success for m in modes)}/{len(modes)} ({_rate(modes):.1%})"]
    if detected:
        handle = np.array([m.handle_error for m in detected]) * 100
        normal = np.array([m.normal_error for m in detected])
        text.append(f"  handle error cm: median {np.median(handle):.2f}, 95% {np.percentile(handle, 95):.2f}, "
                    f"max {handle.max():.2f}; normal error deg: median {np.median(normal):.2f}, "
                    f"95% {np.percentile(normal, 95):.2f}, max {normal.max():.2f}")
    if times.size:
        text.append(f"  time per frame: median {np.median(times):.1f} ms, "
                    f"95% {np.percentile(times, 95):.1f} ms, max {times.max():.1f} ms")
    if failures:
        text.append("  failures: " + ", ".join(f"{k} {v}" for k, v in sorted(failures.items())))
    return "\n".join(text)


def paper_table() -> str:
    """Seed 001 Table II, for comparison."""
    lines = ["Seed 001 Table II (Atlas, DRC): distance | automatic range, result | operator-aided range, result"]
    lines += [f"  {d:>12} | {a:>13}, {ar:<7} | {o:>13}, {orr}" for d, a, ar, o, orr in PAPER_TABLE_II]
    return "\n".join(lines)


def report(outcomes: Sequence[SceneOutcome], grid: EvaluationGrid) -> str:
    """The full text report."""
    parts = [f"{len(outcomes)} scenes; success = handle within {HANDLE_TOLERANCE * 100:.0f} cm and normal "
             f"within {NORMAL_TOLERANCE_DEG:.0f}°; depth noise k ∈ {list(grid.noises)} (σ = k·z²)"]
    for mode in ("automatic", "operator"):
        parts += ["", f"== {mode} (successes / scenes per distance × viewing angle) ==",
                  success_table(outcomes, mode, grid), summary(outcomes, mode)]
    parts += ["", paper_table()]
    return "\n".join(parts)


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="4 distances × 3 angles, no noise")
    parser.add_argument("--colours", choices=("cycle", "all"), default="cycle",
                        help="cycle colour pairs over the cells, or run every pair in every cell")
    parser.add_argument("--noise", type=float, nargs="+", default=None,
                        help="depth noise coefficients k (σ = k·z²), default 0 0.003")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--no-progress", action="store_true")
    args = parser.parse_args(argv)
    grid = EvaluationGrid(seed=args.seed, all_colours=args.colours == "all")
    if args.quick:
        grid = EvaluationGrid((1.0, 2.0, 3.0, 4.0), (-0.6, 0.0, 0.6), (0.0,), grid.all_colours, args.seed)
    if args.noise is not None:
        grid = EvaluationGrid(grid.distances, grid.yaws, tuple(args.noise), grid.all_colours, grid.seed)
    outcomes = run_evaluation(grid, progress=not args.no_progress)
    print(report(outcomes, grid))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
