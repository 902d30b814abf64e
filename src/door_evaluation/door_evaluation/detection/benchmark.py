"""Time per 1024×544 frame of both detectors on rendered sim-core scenes, against the paper.

``python -m door_evaluation.detection.benchmark [--repeats N]``

[Banerjee 2015] Table I: door detection took 20.5 s (pull door) / 19.6 s (push door) for the
10-frame vote, i.e. ~2 s per frame; the project's target (DESIGN.md) is ≤ 50 ms per
1024×544 frame on one core.  OpenCV is limited to one thread here; the frames are rendered
once (rendering is the simulator's cost, not the detector's) and each detector runs
``repeats`` times per scene.  Prints per scene and overall the median and 95th percentile,
the paper's figure, and the speed-up ratio.
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import cv2
import numpy as np

from door_detection.automatic import detect_automatic
from door_detection.errors import InputError
from door_detection.estimate import DetectionResult
from door_detection.operator_aided import detect_from_scribble
from door_detection.options import DetectionOptions
from door_detection.progress import ProgressBar
from door_evaluation.detection.sim_scenes import Scenario, SceneFrame, render_scenario

__all__ = ["benchmark_scene", "main", "report"]

PAPER_SECONDS_PER_VOTE = 20.5
"""[Banerjee 2015] Table I, pull door: detection time for the 10-frame vote (s)."""
PAPER_FRAMES_PER_VOTE = 10
TARGET_SECONDS_PER_FRAME = 0.050
SCENARIOS = (Scenario(1.0, 0.0), Scenario(2.0, 0.0), Scenario(2.0, 0.4, depth_noise=0.003),
             Scenario(3.0, -0.4, depth_noise=0.003), Scenario(4.0, 0.0, depth_noise=0.003))


@dataclass(frozen=True)
class Timing:
    """Wall times (s) of one detector on one scene, and whether every run succeeded."""

    label: str
    seconds: tuple[float, ...]
    success: bool

    @property
    def median(self) -> float:
        return float(np.median(self.seconds))

    @property
    def p95(self) -> float:
        return float(np.percentile(self.seconds, 95))


def time_detector(run: Callable[[], DetectionResult], repeats: int, label: str) -> Timing:
    """Call ``run`` ``repeats`` times (after one warm-up call) and time each call."""
    ok = run().ok
    seconds = []
    for _ in range(repeats):
        start = time.perf_counter()
        ok = run().ok and ok
        seconds.append(time.perf_counter() - start)
    return Timing(label, tuple(seconds), ok)


def benchmark_scene(frame: SceneFrame, options: DetectionOptions, repeats: int) -> tuple[Timing, Timing]:
    """Automatic and operator-aided timings on one rendered frame."""
    s, scribble = frame.scenario, frame.scribble
    name = f"{s.distance:.1f} m, {s.yaw:+.1f} rad, k={s.depth_noise:g}"
    if scribble is None:
        raise InputError(f"{name}: the lever is not in view, there is nothing to scribble on")
    automatic = time_detector(lambda: detect_automatic(frame.rgb, frame.depth, frame.intrinsics, options),
                              repeats, name)
    operator = time_detector(lambda: detect_from_scribble(frame.rgb, frame.depth, frame.intrinsics,
                                                          scribble, options, s.hinge_side, frame.up),
                             repeats, name)
    return automatic, operator


def report(rows: Sequence[tuple[Timing, Timing]]) -> str:
    """The per-scene table and the comparison with the paper."""
    paper = PAPER_SECONDS_PER_VOTE / PAPER_FRAMES_PER_VOTE
    lines = ["scene                        | automatic median / p95 ms | operator-aided median / p95 ms",
             "-" * 90]
    for automatic, operator in rows:
        lines.append(f"{automatic.label:<28} | {_cell(automatic):<25} | {_cell(operator)}")
    lines.append("")
    for mode, index in (("automatic", 0), ("operator-aided", 1)):
        every = np.concatenate([row[index].seconds for row in rows])
        median = float(np.median(every))
        lines.append(f"{mode:>15}: paper {paper * 1e3:6.0f} ms/frame ({PAPER_SECONDS_PER_VOTE} s per "
                     f"{PAPER_FRAMES_PER_VOTE}-frame vote), ours {median * 1e3:5.1f} ms/frame median, "
                     f"{np.percentile(every, 95) * 1e3:5.1f} ms p95 → {paper / median:5.0f}× faster; "
                     f"10-frame vote {10 * median:.2f} s; target {TARGET_SECONDS_PER_FRAME * 1e3:.0f} ms "
                     f"{'met' if np.percentile(every, 95) <= TARGET_SECONDS_PER_FRAME else 'NOT met'}")
    return "\n".join(lines)


def _cell(timing: Timing) -> str:
    flag = "" if timing.success else "  (detection failed)"
    return f"{timing.median * 1e3:7.1f} / {timing.p95 * 1e3:5.1f}{flag}"


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=20, help="timed runs per scene and detector")
    parser.add_argument("--no-progress", action="store_true")
    args = parser.parse_args(argv)
    cv2.setNumThreads(1)
    options = DetectionOptions()
    bar = ProgressBar(len(SCENARIOS), enabled=not args.no_progress)
    rows = []
    for scenario in SCENARIOS:
        rows.append(benchmark_scene(render_scenario(scenario), options, max(args.repeats, 1)))
        bar.advance(f"d={scenario.distance:.1f} m")
    bar.close()
    print(f"1024×544 frames, OpenCV threads: {cv2.getNumThreads()}, {max(args.repeats, 1)} runs per scene")
    print(report(rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
