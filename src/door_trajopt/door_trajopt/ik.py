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

from dataclasses import dataclass

import numpy as np

from door_trajopt.chain import ArmChain
from door_trajopt.door_model import rotation_vector
from door_trajopt.problem import TrajoptError

__all__ = ["IkOptions", "IkResult", "pose_error", "solve_ik", "solve_ik_multistart"]


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
    rows = np.ones(6, dtype=bool) if mask is None else np.asarray(mask, dtype=bool)
    q = np.clip(np.asarray(seed, dtype=float), chain.lower, chain.upper)
    error = pose_error(chain.tcp_pose(q), target) * rows
    size, centring = _error_size(error), options.centring_gain
    for _ in range(options.max_iterations):
        if (np.linalg.norm(error[:3]) < options.position_tolerance
                and np.linalg.norm(error[3:]) < options.rotation_tolerance):
            break
        step = _limited_step(chain, chain.tcp_jacobian(q)[rows], error[rows], q, centring, options)
        q = np.clip(q + step, chain.lower, chain.upper)
        error = pose_error(chain.tcp_pose(q), target) * rows
        previous, size = size, _error_size(error)
        if size > (1.0 - options.progress) * previous:
            if centring == 0.0:
                break
            centring = 0.0
    position, rotation = float(np.linalg.norm(error[:3])), float(np.linalg.norm(error[3:]))
    return IkResult(q, position, rotation,
                    position < options.position_tolerance * 10 and rotation < options.rotation_tolerance * 10)


def _error_size(error: np.ndarray) -> float:
    """|e_p| + 0.1 |e_R| (m; 0.1 m per rad) of an error vector, as :attr:`IkResult.miss`."""
    return float(np.linalg.norm(error[:3]) + 0.1 * np.linalg.norm(error[3:]))


def _limited_step(chain: ArmChain, jacobian: np.ndarray, error: np.ndarray, q: np.ndarray,
                  centring: float, options: IkOptions) -> np.ndarray:
    """δq of the module docstring; joints pushed against their limits are frozen."""
    free = np.ones(q.size, dtype=bool)
    pull = centring * (0.5 * (chain.lower + chain.upper) - q)
    step = np.zeros(q.size)
    for _ in range(3):  # freezing a joint can make another one push out: a few passes
        step = np.zeros(q.size)
        step[free] = _task_and_null_space_step(jacobian[:, free], error, pull[free], options.damping)
        blocked = free & (((q <= chain.lower) & (step < 0.0)) | ((q >= chain.upper) & (step > 0.0)))
        if not blocked.any() or blocked.sum() == free.sum():
            break
        free &= ~blocked
    largest = np.max(np.abs(step))
    return step * (options.max_step / largest) if largest > options.max_step else step


def _task_and_null_space_step(jacobian: np.ndarray, error: np.ndarray, pull: np.ndarray,
                              damping: float) -> np.ndarray:
    """J⁺e + (I − V_r V_rᵀ) pull from one SVD of J."""
    left, singular, right_t = np.linalg.svd(jacobian, full_matrices=False)
    task = right_t.T @ ((singular / (singular**2 + damping**2)) * (left.T @ error))
    ranged = right_t[singular > 1e-9 * max(float(singular[0]), 1e-300)]
    step: np.ndarray = task + pull - ranged.T @ (ranged @ pull)
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
