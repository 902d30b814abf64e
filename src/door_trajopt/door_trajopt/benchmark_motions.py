"""Benchmark: each door motion on TALOS, both backends (seed 001: 10.1–21 s per plan).

    python -m door_trajopt.benchmark_motions [--repeats 3]

The door stands where the footstep planner's stand pose puts it (grasp point 0.44 m ahead
and 0.2 m to the right of the base); the motions are chained as the FSM runs them:
approach → turn → push, each from the previous one's end. Prints the median planning time
per motion and backend, the paper's figure and the ratio; target ≤ 200 ms.
"""

from __future__ import annotations

import argparse
import statistics

import numpy as np

from door_robot.kinematics import RobotKinematics
from door_robot.profile import Side, load_profile
from door_trajopt.chain import ArmChain
from door_trajopt.door_model import DoorModel
from door_trajopt.library import Backend, MotionLibrary
from door_trajopt.motions import Motion, MotionSetup, start_door_for, support_polygon

PAPER_SECONDS = {Motion.APPROACH_HANDLE: 10.1, Motion.TURN_HANDLE: 10.1, Motion.PUSH_DOOR: 15.5}
TARGET_SECONDS = 0.2


def standard_setup() -> tuple[ArmChain, DoorModel]:
    kinematics = RobotKinematics(load_profile("talos"))
    chain = ArmChain(kinematics, Side.RIGHT, kinematics.nominal_q.copy())
    grasp = np.array([0.44, -0.20, 0.91 - kinematics.profile.base_height])
    door = DoorModel(grasp, np.array([-1.0, 0.0, 0.0]), grasp + np.array([0.10, 0.778, 0.0]), push=True)
    return chain, door


def run(repeats: int) -> list[tuple[str, str, float, bool]]:
    chain, door = standard_setup()
    rows = []
    for backend in Backend:
        library = MotionLibrary()
        times: dict[Motion, list[float]] = {m: [] for m in PAPER_SECONDS}
        succeeded: dict[Motion, bool] = {m: True for m in PAPER_SECONDS}
        for _ in range(repeats):
            q, angle = chain.chain_of(chain.body_q), 0.0
            for motion in PAPER_SECONDS:
                setup = MotionSetup(chain, door, 0.914, support_polygon(chain),
                                    start_door_for(motion, angle, library.options))
                plan = library.plan(motion, setup, q, backend)
                times[motion].append(plan.planning_time_s)
                succeeded[motion] &= plan.succeeded
                if plan.succeeded:
                    q, angle = plan.result.trajectory[-1, :chain.size], plan.final_door[0]
                library._cache.clear()  # measure cold plans, not cache hits
        rows += [(motion.value, backend.value, statistics.median(times[motion]), succeeded[motion])
                 for motion in PAPER_SECONDS]
    return rows


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args(argv)
    print(f"| motion | backend | paper | ours (median of {args.repeats}) | paper/ours | target 200 ms | ok |")
    print("|---|---|---|---|---|---|---|")
    for motion, backend, seconds, ok in run(args.repeats):
        paper = PAPER_SECONDS[Motion(motion)]
        print(f"| {motion} | {backend} | {paper:.1f} s | {seconds * 1000:.0f} ms | {paper / seconds:.0f}× | "
              f"{'met' if seconds <= TARGET_SECONDS else 'missed'} | {'yes' if ok else 'FAILED'} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
