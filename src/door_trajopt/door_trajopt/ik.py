"""Inverse kinematics of an arm chain by damped least squares (for key poses / initial guesses).

Seed 001 Sec. IV and seed 000 Sec. III build initial trajectories by interpolating key
poses solved by IK. Each iteration solves δq = J⁺e + (I − J⁺J) k (q_mid − q) with the damped pseudo-inverse
J⁺ = Jᵀ(JJᵀ + λ²I)⁻¹, the 6-D pose error e = (p* − p, log(R* Rᵀ)) and a null-space pull
towards the middle of the joint range (so later motions keep room to move), limits the
step, and clamps to the joint limits.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from door_trajopt.chain import ArmChain
from door_trajopt.door_model import rotation_vector


@dataclass(frozen=True)
class IkOptions:
    max_iterations: int = 150
    damping: float = 0.05  # λ
    centring_gain: float = 0.1  # null-space pull towards the middle of the joint range
    max_step: float = 0.3  # rad per iteration
    position_tolerance: float = 1e-4  # m
    rotation_tolerance: float = 1e-3  # rad


@dataclass(frozen=True)
class IkResult:
    chain_q: np.ndarray
    position_error: float  # m
    rotation_error: float  # rad
    converged: bool


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
    for _ in range(options.max_iterations):
        if (np.linalg.norm(error[:3]) < options.position_tolerance
                and np.linalg.norm(error[3:]) < options.rotation_tolerance):
            break
        jacobian = chain.tcp_jacobian(q)[rows]
        pseudo_inverse = jacobian.T @ np.linalg.inv(jacobian @ jacobian.T + options.damping**2 * np.eye(rows.sum()))
        centre = 0.5 * (chain.lower + chain.upper)
        null_space = np.eye(q.size) - pseudo_inverse @ jacobian
        step = pseudo_inverse @ error[rows] + null_space @ (options.centring_gain * (centre - q))
        largest = np.max(np.abs(step))
        if largest > options.max_step:
            step *= options.max_step / largest
        q = np.clip(q + step, chain.lower, chain.upper)
        error = pose_error(chain.tcp_pose(q), target) * rows
    position, rotation = float(np.linalg.norm(error[:3])), float(np.linalg.norm(error[3:]))
    return IkResult(q, position, rotation,
                    position < options.position_tolerance * 10 and rotation < options.rotation_tolerance * 10)


def solve_ik_multistart(chain: ArmChain, target: np.ndarray, seeds: list[np.ndarray],
                        options: IkOptions = IkOptions(), mask: np.ndarray | None = None) -> IkResult:
    """Best of several seeds (first converged one wins)."""
    best = None
    for seed in seeds:
        result = solve_ik(chain, target, seed, options, mask)
        if result.converged:
            return result
        if best is None or result.position_error + 0.1 * result.rotation_error < \
                best.position_error + 0.1 * best.rotation_error:
            best = result
    return best
