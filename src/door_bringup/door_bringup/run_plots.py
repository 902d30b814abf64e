"""Plots of a run, drawn from its rosbag (the bag is the run's complete audit trail).

* ``summary.png``: the one figure of the run (:mod:`door_bringup.summary_figure`): top view,
  door angle, hand–handle distance, centre of mass against the support polygon;
* ``footsteps.png``: top view of the door estimate, the executed footstep plans and the
  base's path from /odom;
* ``trajectories.png``: each planned motion's joints, initial guess (dashed) against the
  optimised trajectory (solid), like [Zucker 2013]'s Fig. 4;
* ``detection.png``: the detector's last debug image (overlay of door and handle).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from rclpy.serialization import deserialize_message  # noqa: E402

from door_bringup.bags.storage import read_messages  # noqa: E402
from door_bringup.summary_figure import plot_summary  # noqa: E402
from door_contract.converters.footsteps import path_to_footsteps  # noqa: E402
from door_contract.converters.image import image_to_array  # noqa: E402
from door_contract.errors import ContractError  # noqa: E402
from door_contract.payloads import MotionFigures, PlanningOutcome, decode  # noqa: E402
from door_contract.topics import Topics, TopicSpec  # noqa: E402
from door_contract.vocabulary import Foot

__all__ = ["planned_motions", "plot_footsteps", "plot_run", "plot_trajectories", "save_detection"]


def _messages(bag: Path, topic: TopicSpec) -> list[Any]:
    """``topic``'s messages in ``bag``, decoded (ROS 2's generated message classes carry no types)."""
    return [deserialize_message(m.data, topic.msg_class()) for m in read_messages(bag, [topic.name])]


def plot_footsteps(bag: Path, output: Path) -> Path | None:
    plans = _messages(bag, Topics.FOOTSTEP_PLAN)
    odometry = _messages(bag, Topics.ODOM)
    estimates = [json.loads(m.data) for m in _messages(bag, Topics.DOOR_ESTIMATE)]
    if not (plans or odometry):
        return None
    figure, axes = plt.subplots(figsize=(7, 6))
    if estimates:
        corners = np.array(estimates[-1]["corners"])
        axes.plot(corners[:2, 0], corners[:2, 1], "k-", linewidth=4, label="door (estimate)")
        handle = estimates[-1]["handle_position"]
        axes.plot(handle[0], handle[1], "r*", markersize=12, label="handle")
    for plan in plans:
        for step in path_to_footsteps(plan):
            colour = "tab:blue" if step.foot is Foot.LEFT else "tab:orange"
            axes.add_patch(plt.Rectangle((step.x - 0.11, step.y - 0.065), 0.22, 0.13,
                                         angle=np.degrees(step.yaw), rotation_point="center",
                                         fill=False, edgecolor=colour))
    if odometry:
        path = np.array([[o.pose.pose.position.x, o.pose.pose.position.y] for o in odometry])
        axes.plot(path[:, 0], path[:, 1], "g-", label="base (odom)")
    axes.set_aspect("equal")
    axes.set_xlabel("x (m, odom)")
    axes.set_ylabel("y (m)")
    axes.set_title("Footsteps (blue left, orange right), top view")
    axes.legend(loc="best")
    axes.autoscale_view()
    figure.savefig(output, dpi=110, bbox_inches="tight")
    plt.close(figure)
    return output


def planned_motions(bag: Path) -> list[tuple[PlanningOutcome, MotionFigures]]:
    """The motion outcomes in ``bag`` that carry an optimised trajectory, with their figures (an
    outcome that does not decode, as one of an older contract, is left out: nothing to plot)."""
    motions = []
    for message in _messages(bag, Topics.MOTION_OUTCOME):
        try:
            outcome = decode(PlanningOutcome, message.data)
        except ContractError:
            continue
        if outcome.motion is not None and outcome.motion.optimised:
            motions.append((outcome, outcome.motion))
    return motions


def plot_trajectories(bag: Path, output: Path) -> Path | None:
    motions = planned_motions(bag)
    if not motions:
        return None
    figure, axes = plt.subplots(len(motions), 1, figsize=(8, 2.6 * len(motions)), squeeze=False)
    for axis, (outcome, figures) in zip(axes[:, 0], motions):
        guess, optimised = np.array(figures.initial_guess), np.array(figures.optimised)
        for j, name in enumerate(figures.joint_names):
            line, = axis.plot(optimised[:, j], label=name)
            axis.plot(guess[:, j], "--", color=line.get_color(), alpha=0.6)
        axis.set_title(f"request {outcome.request_id}: cost {figures.cost}, "
                       f"{outcome.planning_time_s * 1000:.0f} ms (dashed: initial guess)", fontsize=9)
        axis.set_ylabel("rad")
    axes[-1, 0].set_xlabel("waypoint")
    axes[0, 0].legend(fontsize=6, ncol=3, loc="best")
    figure.tight_layout()
    figure.savefig(output, dpi=100)
    plt.close(figure)
    return output


def save_detection(bag: Path, output: Path) -> Path | None:
    images = list(read_messages(bag, [Topics.DETECTION_DEBUG_IMAGE.name]))
    if not images:
        return None
    image = image_to_array(deserialize_message(images[-1].data, Topics.DETECTION_DEBUG_IMAGE.msg_class()))
    plt.imsave(output, image)
    return output


def plot_run(run_dir: Path, opening: str | None = None, robot: str = "talos") -> list[Path]:
    """Every plot the run's bag allows (``robot``: the run's robot profile); returns the files written."""
    bag = run_dir / "bag"
    if not (bag / "metadata.yaml").is_file():
        return []
    written = [plot_summary(bag, run_dir / "summary.png", robot, opening),
               plot_footsteps(bag, run_dir / "footsteps.png"),
               plot_trajectories(bag, run_dir / "trajectories.png"),
               save_detection(bag, run_dir / "detection.png")]
    return [path for path in written if path is not None]
