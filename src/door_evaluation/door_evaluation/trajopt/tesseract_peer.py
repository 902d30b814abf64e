"""The peer: tesseract's TrajOpt (trajopt_sco's trust-region SQP with OSQP) on a :class:`PeerProblem`.

An optional extra, not a requirement of the project: ``tesseract-robotics`` from PyPI
(:data:`INSTALL_COMMAND`; its newer ``tesseract-robotics-nanobind`` wheels need a libstdc++
with GLIBCXX_3.4.31, newer than Debian 12's). Only this module imports it, and only when
called.

The same problem as the project's, in TrajOpt's own terms (``ProblemConstructionInfo``):
``n_steps`` waypoints initialised STATIONARY, the URDF joint limits, waypoint 0 held at the
start by a joint-position constraint, the squared joint-velocity cost
``sum_t ||q_t - q_{t-1}||^2`` (coefficient 1, TrajOpt's definition), and a Cartesian pose
constraint per target: TCP = the profile's TCP parent link with its grasp offset, target in
the profile's base frame. The robot's other joints stand where the Pinocchio model has them
(:attr:`ArmChain.body_q`); the URDF is loaded without meshes (no collision terms: the
project's problem has none either).
"""

from __future__ import annotations

import importlib.util
import time
import xml.etree.ElementTree as ElementTree
from dataclasses import dataclass
from types import ModuleType
from typing import Any

import numpy as np

from door_evaluation.trajopt.peer_problems import PeerProblem

__all__ = ["INSTALL_COMMAND", "PeerRun", "TrajOptPeer", "tesseract_available"]

INSTALL_COMMAND = ".venv/bin/pip install tesseract-robotics==0.5.1"
GROUP = "manipulator"


def tesseract_available() -> bool:
    return importlib.util.find_spec("tesseract_robotics") is not None


@dataclass(frozen=True)
class PeerRun:
    trajectory: np.ndarray  # (T, k)
    seconds: float  # problem construction and solve (the project's timings build their solver too)


def _urdf_without_meshes(path: str) -> str:
    tree = ElementTree.parse(path)
    for link in tree.getroot().iter("link"):
        for tag in ("visual", "collision"):
            for element in link.findall(tag):
                link.remove(element)
    return ElementTree.tostring(tree.getroot(), encoding="unicode")


def _parent_link(urdf_path: str, joint_name: str) -> str:
    for joint in ElementTree.parse(urdf_path).getroot().iter("joint"):
        if joint.get("name") != joint_name:
            continue
        parent = joint.find("parent")
        link = None if parent is None else parent.get("link")
        if link is None:
            raise ValueError(f"{urdf_path}: joint {joint_name!r} names no parent link")
        return link
    raise ValueError(f"{urdf_path} has no joint {joint_name!r}")


def _srdf(robot: str, base_link: str, tip_link: str) -> str:
    return (f'<?xml version="1.0"?><robot name="{robot}"><group name="{GROUP}">'
            f'<chain base_link="{base_link}" tip_link="{tip_link}"/></group></robot>')


class TrajOptPeer:
    """A tesseract environment of the profile's robot with the peer problem's arm as a group."""

    def __init__(self, peer: PeerProblem, tolerance: float, max_iterations: int) -> None:
        from tesseract_robotics.tesseract_common import GeneralResourceLocator
        from tesseract_robotics.tesseract_environment import Environment

        chain, profile = peer.chain, peer.chain.kinematics.profile
        urdf_path = str(profile.urdf_path)
        self.peer, self.tolerance, self.max_iterations = peer, tolerance, max_iterations
        self.tip = profile.arm(chain.side).tcp_parent_frame
        self.offset = np.asarray(profile.arm(chain.side).grasp_offset, dtype=float)
        self.base_frame = profile.base_frame
        urdf = _urdf_without_meshes(urdf_path)
        srdf = _srdf(ElementTree.fromstring(urdf).get("name", "robot"),
                     _parent_link(urdf_path, chain.joint_names[0]), self.tip)
        self.environment = Environment()
        if not self.environment.init(urdf, srdf, GeneralResourceLocator()):
            raise RuntimeError("tesseract could not load the robot")
        self.environment.setState(list(chain.kinematics.joint_names), np.asarray(chain.body_q, dtype=float))
        self.group = self.environment.getJointGroup(GROUP)
        if tuple(self.group.getJointNames()) != chain.joint_names:
            raise RuntimeError(f"tesseract's chain {tuple(self.group.getJointNames())} is not {chain.joint_names}")

    def solve(self) -> PeerRun:
        """Construct and optimise (STATIONARY initial trajectory, as the project's runs)."""
        from tesseract_robotics.tesseract_motion_planners_trajopt import tesseract_motion_planners_trajopt_python

        started = time.perf_counter()
        problem = self._construct()
        # the module's Python wrapper passes a null plotter SWIG cannot convert: call the C entry
        result = tesseract_motion_planners_trajopt_python._tesseract_motion_planners_trajopt_python.OptimizeProblem(problem)
        seconds = time.perf_counter() - started
        return PeerRun(np.asarray(result.traj, dtype=float).reshape(self.peer.n_waypoints, -1), seconds)

    def _construct(self) -> Any:
        """The Tesseract TrajOpt problem (the bindings are untyped)."""
        import tesseract_robotics.tesseract_motion_planners_trajopt as trajopt

        peer, k = self.peer, self.peer.chain.size
        info = trajopt.ProblemConstructionInfo(self.environment)
        info.basic_info.n_steps = peer.n_waypoints
        info.basic_info.manip = GROUP
        info.basic_info.use_time = False
        info.basic_info.convex_solver = trajopt.ModelType(trajopt.ModelType.OSQP)
        info.init_info.type = trajopt.InitInfo.STATIONARY
        info.opt_info.cnt_tolerance = self.tolerance
        info.opt_info.max_iter = self.max_iterations
        info.kin = self.group
        start = trajopt.JointPosTermInfo()
        start.name, start.term_type, start.first_step, start.last_step = "start", trajopt.TermType_TT_CNT, 0, 0
        start.coeffs, start.targets = np.ones(k), peer.start.copy()
        info.cnt_infos.append(start)
        velocity = trajopt.JointVelTermInfo()
        velocity.name, velocity.term_type = "velocity", trajopt.TermType_TT_COST
        velocity.first_step, velocity.last_step = 0, peer.n_waypoints - 1
        velocity.coeffs, velocity.targets = np.ones(k), np.zeros(k)
        info.cost_infos.append(velocity)
        for t, pose in peer.targets:
            info.cnt_infos.append(self._pose_term(trajopt, t, pose))
        return trajopt.ConstructProblem(info)

    def _pose_term(self, trajopt: ModuleType, waypoint: int, pose: np.ndarray) -> Any:
        from tesseract_robotics.tesseract_common import Isometry3d

        tcp = np.eye(4)
        tcp[:3, 3] = self.offset
        term = trajopt.CartPoseTermInfo()
        term.name, term.term_type, term.timestep = f"pose_{waypoint}", trajopt.TermType_TT_CNT, waypoint
        term.source_frame, term.target_frame = self.tip, self.base_frame
        term.source_frame_offset, term.target_frame_offset = Isometry3d(tcp), Isometry3d(np.array(pose))
        term.pos_coeffs, term.rot_coeffs = np.ones(3), np.ones(3)
        return term
