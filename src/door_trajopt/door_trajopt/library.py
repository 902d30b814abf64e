"""Plan door motions: build the problem, optimise (SQP or constrained CHOMP), time it.

Multi-start as [Banerjee 2015] Sec. IV: first the IK-keyed initial guess (or the cached last
feasible solution of the same motion when it starts where this one does), then guesses
through a random middle state. The first feasible result wins.

The work of one plan is bounded deterministically: at most ``starts + attempt`` guesses
(plus the cached one on a first attempt), each at most ``max_iterations · (1 + attempt)``
iterations (capped at ``MAX_ATTEMPT_SCALE``×). ``time_budget_s`` is only a safety net far
above normal use (a plan takes ~0.1 s): no further guess is started after it. A door state
outside the door's stops is refused before any work (:class:`DoorStateOutOfRange`).
"""

from __future__ import annotations

import time
from collections.abc import Iterator
from dataclasses import dataclass, field, replace

import numpy as np

from door_contract.converters.trajectory import JointPath
from door_contract.vocabulary import Backend, Motion
from door_trajopt.chomp import ChompOptions, ChompSolver
from door_trajopt.motions import (
    MotionOptions,
    MotionProblem,
    MotionSetup,
    anchored_to_hand,
    build_motion,
    check_start_door,
    minimum_duration,
)
from door_trajopt.problem import TrajoptError
from door_trajopt.result import OptimizationResult, Outcome
from door_trajopt.sqp import SqpOptions, SqpSolver
from door_trajopt.timing import time_parameterise

__all__ = ["MotionLibrary", "MotionPlan"]

MAX_ATTEMPT_SCALE = 4  # a repeat gets at most this many times the first attempt's iterations


@dataclass(frozen=True)
class MotionPlan:
    motion: Motion
    result: OptimizationResult
    path: JointPath | None  # the chain's joints only, time-parameterised
    final_door: tuple[float, float]  # θ, φ at the end (rad)
    attempts: int
    planning_time_s: float
    initial_guess: np.ndarray | None = None  # (n, m) the guess the result was optimised from
    guess_time_s: float = 0.0  # building the problem and its IK-keyed initial guess (wall)
    guess_cpu_s: float = 0.0  # the same in this process's CPU time (a loaded machine's wall time is longer)

    @property
    def succeeded(self) -> bool:
        return self.result.outcome is Outcome.SUCCESS and self.path is not None


@dataclass
class MotionLibrary:
    options: MotionOptions = field(default_factory=MotionOptions)
    starts: int = 3  # initial guesses tried ([Banerjee 2015] Sec. IV: multiple random guesses)
    velocity_scale: float = 0.5
    door_velocity_limits: tuple[float, float] = (0.15, 0.5)  # rad/s of hinge and handle: a door is heavy
    max_iterations: int = 120  # per initial guess (SQP QP solves / CHOMP updates)
    time_budget_s: float = 40.0  # safety net only (plans take ~0.1 s): no further guess after this; below the
    # FSM's 60 s planning timeout. At 10 s, with two graphs on the 2 cores, the second and third repeats of an
    # infeasible turn (2-3 s a guess) got 4 of 5 and 5 of 6 guesses (Monte-Carlo seed 11, stop 39): load chose the work
    constraint_tolerance: float = 1e-5  # m / rad: 10 µm on the handle (SQP stalled at ~5 µm once)
    cost_tolerance: float = 1e-6  # relative cost/merit change deemed converged
    seed: int = 0
    _cache: dict[Motion, np.ndarray] = field(default_factory=dict)  # motion → last feasible trajectory (n, m)

    def plan(self, motion: Motion, setup: MotionSetup, start_chain: np.ndarray,
             backend: Backend = Backend.SQP, variant: int = 0, attempt: int = 0) -> MotionPlan:
        """Plan ``motion``; ``variant`` salts the random initial guesses. ``attempt`` counts the
        repeats of one request (0 first, +1 per repeat: the operator's "repeat", the FSM's
        automatic retry): a repeat does not reuse the cached trajectory, tries ``attempt``
        more random guesses, salted by the attempt, and allows more iterations per guess.
        Raises :class:`DoorStateOutOfRange` for a door state outside the door's stops."""
        started, started_cpu = time.perf_counter(), time.process_time()
        if isinstance(attempt, bool) or not isinstance(attempt, int) or attempt < 0:
            raise TrajoptError(f"attempt must be an integer >= 0, got {attempt!r}")
        check_start_door(setup.start_door)
        if motion.holds_handle:
            setup = anchored_to_hand(setup, start_chain)
        built = build_motion(motion, setup, start_chain, self.options)
        guess_time, guess_cpu = time.perf_counter() - started, time.process_time() - started_cpu
        rng = np.random.default_rng([self.seed, variant] + ([attempt] if attempt else []))
        iterations = self.max_iterations * min(1 + attempt, MAX_ATTEMPT_SCALE)
        solver = (SqpSolver(built.problem, SqpOptions(max_iterations=iterations,
                                                      constraint_tolerance=self.constraint_tolerance,
                                                      cost_tolerance=self.cost_tolerance,
                                                      constraint_curvature=True))
                  if backend is Backend.SQP else
                  ChompSolver(built.problem, ChompOptions(max_iterations=iterations,
                                                          constraint_tolerance=self.constraint_tolerance,
                                                          cost_tolerance=self.cost_tolerance)))
        result: OptimizationResult | None = None
        attempts, used_guess = 0, None
        for guess in self._guesses(motion, built, rng, attempt):  # one solver: its factorisation is reused
            if attempts and time.perf_counter() - started > self.time_budget_s:
                break
            attempts += 1
            result, used_guess = self._feasible_is_enough(solver.solve(guess)), guess
            if result.outcome is Outcome.SUCCESS:
                self._cache[motion] = result.trajectory
                break
        if result is None:  # not reached: the first guess is always tried
            raise TrajoptError(f"{motion.value}: no initial guess was tried")
        k = built.chain.size
        path = None
        if result.outcome is Outcome.SUCCESS:
            # timed over robot and door DOFs, so the door is never swung faster than it can follow
            limits = np.concatenate([built.chain.velocity_limits * self.velocity_scale, self.door_velocity_limits])
            timed = time_parameterise(result.trajectory, built.problem.dof_names, limits,
                                      minimum_duration=minimum_duration(motion, self.options))
            velocities = None if timed.velocities is None else timed.velocities[:, :k]
            path = JointPath(timed.times, built.chain.joint_names, timed.positions[:, :k], velocities)
        final = (float(result.trajectory[-1, k]), float(result.trajectory[-1, k + 1]))  # (θ, φ)
        return MotionPlan(motion, result, path, final, attempts, time.perf_counter() - started, used_guess,
                          guess_time, guess_cpu)

    def clear_cache(self) -> None:
        """Forget the last feasible trajectories (the next plans start cold)."""
        self._cache.clear()

    def _feasible_is_enough(self, result: OptimizationResult) -> OptimizationResult:
        """A motion needs a feasible, smooth trajectory, not the last digit of its cost: an
        iteration-limited result within the constraint tolerance is used (the SQP once
        crawled for 120 iterations at a feasible point while its merit kept moving)."""
        if result.outcome is Outcome.ITERATION_LIMIT and result.max_violation <= self.constraint_tolerance:
            return replace(result, outcome=Outcome.SUCCESS,
                           message=f"feasible at the iteration limit after {result.iterations} iterations")
        return result

    def _guesses(self, motion: Motion, built: MotionProblem, rng: np.random.Generator,
                 attempt: int) -> Iterator[np.ndarray]:
        """The cached trajectory (first attempt only), the IK guess, then random ones."""
        cached = self._cache.get(motion) if attempt == 0 else None
        if cached is not None and cached.shape == built.initial_guess.shape and \
                np.allclose(cached[0], built.problem.start, atol=1e-3):
            yield cached
        yield built.initial_guess
        lower, upper = built.problem.limits.lower, built.problem.limits.upper
        n = built.problem.n_waypoints
        for _ in range(self.starts - 1 + attempt):  # linear interpolation through a random middle state
            middle = np.clip(built.initial_guess[n // 2] + rng.normal(0.0, 0.2, lower.size), lower, upper)
            ratio = np.abs(np.linspace(-1.0, 1.0, n))[:, None]
            guess = ratio * built.initial_guess + (1.0 - ratio) * middle
            guess[0] = built.problem.start
            yield guess
