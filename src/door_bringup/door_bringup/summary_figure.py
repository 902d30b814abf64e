"""``summary.png``: one figure of a run (data and its derivation: :mod:`door_bringup.summary_data`).

* top view: the door estimate and the sector its leaf sweeps, every executed footstep, the
  base's path and the centre of mass's ground track;
* door angle (simulated hinge) over sim time, with the FSM's states as bands;
* hand–handle distance of each hand over sim time (the grasp closes within 2 cm);
* the centre of mass's margin to the edge of the support polygon (+ inside) over sim time, and
  the support polygon with the CoM where that margin was smallest.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from door_bringup.summary_data import RunSeries, read_run  # noqa: E402
from door_contract.vocabulary import Foot, TaskState
from door_viz.proposals import leaf_axes  # noqa: E402

if TYPE_CHECKING:
    from matplotlib.axes import Axes

__all__ = ["plot_summary"]

GRASP_DISTANCE_M = 0.02
FOOT_COLOURS = {Foot.LEFT: "tab:blue", Foot.RIGHT: "tab:orange"}
HAND_COLOURS = {"left": "tab:blue", "right": "tab:red"}


def _top_view(axes: Axes, run: RunSeries, foot_size: tuple[float, float]) -> None:
    if run.estimate is not None:
        corners = np.array(run.estimate.corners)
        axes.plot(corners[:2, 0], corners[:2, 1], "k-", linewidth=4, label="door (estimate, closed)")
        hinge, u, s, width = leaf_axes(run.estimate, run.opening)
        arc = np.array([hinge + width * (math.cos(a) * u + math.sin(a) * s) for a in np.linspace(0, math.pi / 2, 30)])
        axes.fill(np.r_[hinge[0], arc[:, 0]], np.r_[hinge[1], arc[:, 1]], color="gold", alpha=0.25,
                  label=f"leaf's sweep ({run.opening})")
        axes.plot(*run.estimate.handle_position[:2], "r*", markersize=12, label="handle (estimate)")
    for step in run.footsteps:
        axes.add_patch(plt.Rectangle((step.x - foot_size[0] / 2, step.y - foot_size[1] / 2), *foot_size,
                                     angle=math.degrees(step.yaw), rotation_point="center", fill=False,
                                     edgecolor=FOOT_COLOURS[step.foot], linewidth=0.8))
    if len(run.base):
        axes.plot(run.base[:, 1], run.base[:, 2], "g-", label="base (odom)")
    if len(run.com):
        axes.plot(run.com[:, 1], run.com[:, 2], "m:", label="centre of mass")
    axes.set_aspect("equal", adjustable="datalim")
    axes.autoscale_view()
    axes.set(xlabel="x (m, odom)", ylabel="y (m)", title="Top view: footsteps (blue left, orange right)")
    axes.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8)


def _state_bands(axes: Axes, run: RunSeries, end: float) -> None:
    """The FSM's states as shaded bands, labelled once each."""
    changes: list[tuple[float, TaskState | None]] = [*run.states, (end, None)]
    for index, ((start, state), (stop, _)) in enumerate(zip(changes[:-1], changes[1:])):
        if stop > start and state is not None:
            axes.axvspan(start, stop, color=f"C{index % 10}", alpha=0.08)
            axes.text((start + stop) / 2, 1.0, state.value, transform=axes.get_xaxis_transform(),
                      rotation=90, fontsize=6, va="top", ha="center", alpha=0.8)


def _door_angle(axes: Axes, run: RunSeries, end: float) -> None:
    _state_bands(axes, run, end)
    if len(run.door):
        axes.plot(run.door[:, 0], np.degrees(run.door[:, 1]), "k-")
    axes.set(ylabel="door angle (deg)", title="Door angle (simulated hinge) and the FSM's states")


def _hand_distance(axes: Axes, run: RunSeries, end: float) -> None:
    _state_bands(axes, run, end)
    for side, series in run.hands.items():
        if len(series):
            axes.semilogy(series[:, 0], np.maximum(series[:, 1], 1e-3), color=HAND_COLOURS.get(side), label=f"{side} hand")
    axes.axhline(GRASP_DISTANCE_M, color="grey", linestyle="--", linewidth=0.8, label="grasp closes within 2 cm")
    axes.set(ylabel="hand–handle (m)", title="Hand to handle (handle: estimate turned by the hinge angle)")
    axes.legend(loc="best", fontsize=7)


def _com_margin(axes: Axes, run: RunSeries, end: float) -> None:
    _state_bands(axes, run, end)
    if len(run.com):
        axes.plot(run.com[:, 0], run.com[:, 3] * 100.0, "m-")
    axes.axhline(0.0, color="k", linewidth=0.8)
    axes.set(xlabel="sim time (s)", ylabel="CoM margin (cm)",
             title="Centre of mass to the support polygon's edge (+ inside)")


def _support_at_smallest_margin(axes: Axes, run: RunSeries) -> None:
    if not len(run.com):
        return
    worst = int(np.argmin(run.com[:, 3]))
    polygon = np.vstack([run.support[worst], run.support[worst][:1]])
    axes.fill(polygon[:, 0], polygon[:, 1], color="tab:green", alpha=0.2, label="support polygon (both soles)")
    axes.plot(run.com[:, 1], run.com[:, 2], "m:", linewidth=0.8, label="CoM track")
    axes.plot(*run.com[worst, 1:3], "mo", label=f"CoM at t = {run.com[worst, 0]:.1f} s")
    axes.set_aspect("equal", adjustable="box")
    axes.set_xlim(polygon[:, 0].min() - 0.15, polygon[:, 0].max() + 0.15)
    axes.set_ylim(polygon[:, 1].min() - 0.15, polygon[:, 1].max() + 0.15)
    axes.set(xlabel="x (m)", ylabel="y (m)", title=f"Smallest margin: {run.com[worst, 3] * 100:.1f} cm")
    axes.legend(loc="best", fontsize=7)


def plot_summary(bag: Path, output: Path, robot_profile: str = "talos", opening: str | None = None) -> Path | None:
    """Draw ``output`` from the run recorded in ``bag``; None when the bag has no motion."""
    from door_robot.profile import load_profile

    run = read_run(bag, robot_profile, opening)
    if not (len(run.base) or len(run.door)):
        return None
    walking = load_profile(robot_profile).walking
    end = max([run.base[-1, 0] if len(run.base) else 0.0, run.door[-1, 0] if len(run.door) else 0.0])
    figure = plt.figure(figsize=(13, 11))
    grid = figure.add_gridspec(3, 2, height_ratios=(1.1, 1.0, 1.0), width_ratios=(1.6, 1.0))
    _top_view(figure.add_subplot(grid[0, :]), run, (walking.foot_length, walking.foot_width))
    door = figure.add_subplot(grid[1, 0])
    _door_angle(door, run, end)
    _hand_distance(figure.add_subplot(grid[1, 1]), run, end)
    _com_margin(figure.add_subplot(grid[2, 0], sharex=door), run, end)
    _support_at_smallest_margin(figure.add_subplot(grid[2, 1]), run)
    figure.suptitle(f"Door task: {run.opening} door, last state {run.states[-1][1].label if run.states else '?'}")
    figure.tight_layout()
    figure.savefig(output, dpi=100)
    plt.close(figure)
    return output
