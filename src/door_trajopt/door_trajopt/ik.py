"""Inverse kinematics of an arm chain by damped least squares (for key poses / initial guesses).

[Banerjee 2015] Sec. IV and [Zucker 2013] Sec. III build initial trajectories by interpolating key
poses solved by IK. Each iteration solves δq = J⁺e + N k (q_mid − q) with the damped pseudo-inverse
J⁺ = V diag(σ/(σ² + λ²)) Uᵀ (J = U Σ Vᵀ), the 6-D pose error e = (p* − p, log(R* Rᵀ)) and a
pull towards the middle of the joint range (so later motions keep room to move) projected
by the exact null-space projector N = I − V_r V_rᵀ of the non-zero singular directions, so
that it never works against the pose. A joint at a limit that the step would push further
out is frozen (its column dropped) and the step solved again. The step is limited and
clamped to the joint limits.

The pull keeps moving the arm along its self-motion, and each such move costs a little
pose error (second order), so the error settles a few mm off. When an iteration no longer
reduces the error by ``progress``, the pull is switched off and the pose is finished
alone; when that stalls too, the target is out of reach and the IK stops rather than
creep. At most ``max_iterations``: a deterministic budget. (A damped inverse with the unprojected
pull of earlier versions never converged: at a clamped joint the pull and the pose fought
to a standstill 5 mm off, and every solve ran its 150 iterations.)
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from door_trajopt.chain import ArmChain
from door_trajopt.door_model import rotation_vector
from door_trajopt.problem import TrajoptError

__all__ = ["IkOptions", "IkResult", "pose_error", "solve_ik", "solve_ik_batch", "solve_ik_multistart"]


@dataclass(frozen=True)
class IkOptions:
    max_iterations: int = 150
    damping: float = 0.05  # λ
    centring_gain: float = 0.1  # null-space pull towards the middle of the joint range
    max_step: float = 0.3  # rad per iteration
    position_tolerance: float = 1e-4  # m
    rotation_tolerance: float = 1e-3  # rad
    progress: float = 1e-3  # relative error decrease per iteration below which it stops


@dataclass(frozen=True)
class IkResult:
    chain_q: np.ndarray
    position_error: float  # m
    rotation_error: float  # rad
    converged: bool

    @property
    def miss(self) -> float:
        """|e_p| + 0.1 |e_R| (m; 0.1 m per rad): how :func:`solve_ik_multistart` ranks results."""
        return self.position_error + 0.1 * self.rotation_error


def pose_error(current: np.ndarray, target: np.ndarray) -> np.ndarray:
    """(p* − p, log(R* Rᵀ)) in world-aligned axes."""
    return np.concatenate([target[:3, 3] - current[:3, 3],
                           rotation_vector(target[:3, :3] @ current[:3, :3].T)])


def solve_ik(chain: ArmChain, target: np.ndarray, seed: np.ndarray,
             options: IkOptions = IkOptions(), mask: np.ndarray | None = None) -> IkResult:
    """IK of the TCP to ``target``; ``mask`` (6,) of 0/1 selects the pose rows that matter."""
    return solve_ik_batch(chain, target, [seed], options, mask)[0]


def solve_ik_batch(chain: ArmChain, target: np.ndarray, seeds: Sequence[np.ndarray],
                   options: IkOptions = IkOptions(), mask: np.ndarray | None = None,
                   accept: Callable[[IkResult], bool] | None = None) -> list[IkResult]:
    """:func:`solve_ik` from each of ``seeds`` (at least one), all iterated in lock step;
    ``target`` is one pose (4×4) for all seeds or one per seed (S×4×4).

    Each seed follows exactly its own iteration (its own stops, its own centring switch);
    only the linear algebra of one iteration is done for all running seeds at once (one
    stacked SVD instead of one per seed and freezing pass: numpy's call overhead on a
    6×9 matrix is several times its arithmetic). The forward kinematics stay per seed.

    With ``accept``, what trying the seeds one by one up to the first accepted result
    would give: the results of the seeds up to and including the first one (in seed order)
    whose result ``accept`` takes, or of all seeds when none is taken. A seed after an
    accepted one is dropped at once; the iteration goes on only while an earlier seed may
    still be taken.
    """
    rows = np.ones(6, dtype=bool) if mask is None else np.asarray(mask, dtype=bool)
    limits = _Limits(chain.lower, chain.upper)
    q = np.clip(np.array(seeds, dtype=float).reshape(len(seeds), -1), limits.lower, limits.upper)
    targets = np.broadcast_to(target, (len(q), 4, 4))
    running, finished = _Running.start(chain, targets, rows, q, options), _Finished(options, accept)
    for _ in range(options.max_iterations):
        running = finished.add(running, running.within_tolerance(options))
        if running.index.size == 0:
            break
        step = _limited_steps(limits, running.jacobian, running.error[:, rows], running.q, running.centring, options)
        moved = _Running.at(chain, targets, rows, np.clip(running.q + step, limits.lower, limits.upper),
                            running.index, running.centring)
        stalled = moved.size > (1.0 - options.progress) * running.size
        out_of_reach = stalled & (running.centring == 0.0)  # stalled on the pose alone
        moved.centring[stalled] = 0.0  # stalled with the pull: finish the pose alone
        running = finished.add(moved, out_of_reach)
    finished.add(running, np.ones(running.index.size, dtype=bool))
    return finished.in_seed_order()


@dataclass(frozen=True)
class _Limits:
    """The chain's joint limits, looked up once per solve."""

    lower: np.ndarray
    upper: np.ndarray

    @property
    def middle(self) -> np.ndarray:
        middle: np.ndarray = 0.5 * (self.lower + self.upper)
        return middle


@dataclass(frozen=True)
class _Running:
    """The seeds of :func:`solve_ik_batch` still iterating: their numbers among the seeds,
    configurations (S, k), masked pose errors (S, 6), the errors' position and rotation
    norms, TCP Jacobians of the masked rows (S, r, k), and null-space pull gains."""

    index: np.ndarray
    q: np.ndarray
    error: np.ndarray
    position: np.ndarray
    rotation: np.ndarray
    jacobian: np.ndarray
    centring: np.ndarray

    @classmethod
    def start(cls, chain: ArmChain, targets: np.ndarray, rows: np.ndarray, q: np.ndarray,
              options: IkOptions) -> _Running:
        return cls.at(chain, targets, rows, q, np.arange(len(q)), np.full(len(q), options.centring_gain))

    @classmethod
    def at(cls, chain: ArmChain, targets: np.ndarray, rows: np.ndarray, q: np.ndarray, index: np.ndarray,
           centring: np.ndarray) -> _Running:
        """The seeds numbered ``index`` at configurations ``q`` (one kinematics pass each for the
        pose and the Jacobian; ``targets``: every seed's), with a copy of ``centring`` (the solver
        switches a seed's pull off in it)."""
        error, jacobian = np.empty((len(q), 6)), np.empty((len(q), int(rows.sum()), q.shape[1]))
        for seed, (number, configuration) in enumerate(zip(index, q, strict=True)):
            pose, tcp_jacobian = chain.tcp_pose_and_jacobian(configuration)
            error[seed], jacobian[seed] = pose_error(pose, targets[number]) * rows, tcp_jacobian[rows]
        norms = np.sqrt(np.square(error.reshape(len(q), 2, 3)).sum(axis=2))  # (|e_p|, |e_R|) per seed
        return cls(index, q, error, norms[:, 0], norms[:, 1], jacobian, centring.copy())

    @property
    def size(self) -> np.ndarray:
        """|e_p| + 0.1 |e_R| (m; 0.1 m per rad) of each seed, as :attr:`IkResult.miss`."""
        size: np.ndarray = self.position + 0.1 * self.rotation
        return size

    def within_tolerance(self, options: IkOptions) -> np.ndarray:
        within: np.ndarray = (self.position < options.position_tolerance) & (self.rotation < options.rotation_tolerance)
        return within

    def subset(self, kept: np.ndarray) -> _Running:
        """The seeds flagged in ``kept``."""
        return _Running(self.index[kept], self.q[kept], self.error[kept], self.position[kept], self.rotation[kept],
                        self.jacobian[kept], self.centring[kept])


@dataclass
class _Finished:
    """The results of the seeds of :func:`solve_ik_batch` that stopped (by seed number) and the
    first one ``accept`` took (mutable: filled as the seeds stop)."""

    options: IkOptions
    accept: Callable[[IkResult], bool] | None
    results: dict[int, IkResult] = field(default_factory=dict)
    first_accepted: int | None = None

    def add(self, running: _Running, stopped: np.ndarray) -> _Running:
        """Record the ``stopped`` seeds' results; the seeds still worth iterating: not stopped,
        and before the first accepted one."""
        if not stopped.any():  # (the running seeds were cut at the first accepted one when it stopped)
            return running
        for seed in np.flatnonzero(stopped):
            number = int(running.index[seed])
            result = self.results[number] = _result(running.q[seed], running.error[seed], self.options)
            if self.accept is not None and (self.first_accepted is None or number < self.first_accepted) \
                    and self.accept(result):
                self.first_accepted = number
        kept = ~stopped
        if self.first_accepted is not None:
            kept &= running.index < self.first_accepted
        return running if kept.all() else running.subset(kept)

    def in_seed_order(self) -> list[IkResult]:
        """The results up to the first accepted seed (all seeds before it have stopped), or all."""
        last = max(self.results) if self.first_accepted is None else self.first_accepted
        return [self.results[number] for number in range(last + 1)]


def _result(chain_q: np.ndarray, error: np.ndarray, options: IkOptions) -> IkResult:
    position, rotation = float(np.linalg.norm(error[:3])), float(np.linalg.norm(error[3:]))
    return IkResult(chain_q, position, rotation,
                    position < options.position_tolerance * 10 and rotation < options.rotation_tolerance * 10)


def _limited_steps(limits: _Limits, jacobian: np.ndarray, error: np.ndarray, q: np.ndarray,
                   centring: np.ndarray, options: IkOptions) -> np.ndarray:
    """δq of the module docstring for each seed (rows of ``q``); joints pushed against their
    limits are frozen, seed by seed, and that seed's step solved again. A frozen joint's
    column of J and its pull are zeroed, which is the same step as dropping them: J's row
    space, and so V_r, then has no component along that joint."""
    at_lower, at_upper = q <= limits.lower, q >= limits.upper
    pull = centring[:, None] * (limits.middle - q)
    step = _task_and_null_space_steps(jacobian, error, pull, options.damping)
    free = np.ones(q.shape, dtype=bool)
    for _ in range(2):  # freezing a joint can make another one push out: a few passes
        blocked = free & ((at_lower & (step < 0.0)) | (at_upper & (step > 0.0)))
        again = blocked.any(axis=1) & (blocked != free).any(axis=1)  # some, not all, free joints blocked
        if not again.any():
            break
        free[again] &= ~blocked[again]
        kept = free[again]
        step[again] = kept * _task_and_null_space_steps(jacobian[again] * kept[:, None, :], error[again],
                                                        pull[again] * kept, options.damping)
    largest = np.max(np.abs(step), axis=1)
    limited: np.ndarray = step * (options.max_step / np.maximum(largest, options.max_step))[:, None]
    return limited


def _task_and_null_space_steps(jacobian: np.ndarray, error: np.ndarray, pull: np.ndarray,
                               damping: float) -> np.ndarray:
    """J⁺e + (I − V_r V_rᵀ) pull from one SVD of each J (stacked: ``jacobian`` (S, r, k))."""
    left, singular, right_t = np.linalg.svd(jacobian, full_matrices=False)
    weighted = (singular / (singular**2 + damping**2)) * (error[:, None, :] @ left)[:, 0]  # Σ(Σ² + λ²)⁻¹ Uᵀe
    ranged = right_t * (singular > 1e-9 * np.maximum(singular[:, :1], 1e-300))[:, :, None]  # V_rᵀ
    step: np.ndarray = (weighted[:, None, :] @ right_t)[:, 0] + pull - \
        ((ranged @ pull[:, :, None]).transpose(0, 2, 1) @ ranged)[:, 0]
    return step


def solve_ik_multistart(chain: ArmChain, target: np.ndarray, seeds: list[np.ndarray],
                        options: IkOptions = IkOptions(), mask: np.ndarray | None = None) -> IkResult:
    """Best of several seeds (first converged one wins); at least one seed."""
    best: IkResult | None = None
    for seed in seeds:
        result = solve_ik(chain, target, seed, options, mask)
        if result.converged:
            return result
        if best is None or result.miss < best.miss:
            best = result
    if best is None:
        raise TrajoptError("solve_ik_multistart needs at least one seed")
    return best
