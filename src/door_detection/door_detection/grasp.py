"""The 3-D grasp point of a segmented handle ([Banerjee 2015] Sec. III-A "handle", III-B).

The paper gives "the handle point"; the robot needs a grasp point within 2 cm.  Depth on
a 2-cm lever is sparse and, at 4 m, noisy (σ ≈ 5 cm per pixel for a stereo head), so the
point is built from the door plane (fitted over thousands of points) and the blob's
image geometry, with the handle's own depth used only through medians:

* door-plane coordinates: a along the door's horizontal towards the hinge, b along the
  door's up, n the normal towards the camera; each pixel's ray meets the plane pushed
  forward by a stand-off s (n·(p − p0) = s), giving its (a, b);
* a **lever** (blob longer than ``lever_min_elongation`` times its bar height) is a bar
  on a round rose (the lever's axis).  With the blob rectified on the door face, columns
  one pixel wide along a: the bar's height is the median column height; clearly
  taller columns are the rose, and the middle of their extent is the axis.  The tip is
  the hinge-most bar pixel with its ray cut at the bar's stand-off (median over the
  bar's pixels); the grasp point lies ``lever_grasp_fraction`` of the lever length
  L = tip − axis − bar/2 from the axis, on the bar's centre line;
* anything else (a knob) is grasped at its pixels' centroid ray, at their median
  stand-off.

Stand-offs are medians of the handle pixels' distances to the plane, fused with a prior
(:func:`fused_standoff`) so that a handle seen in very noisy depth is not pushed into or
far out of the door.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from door_contract.converters.camera_info import CameraIntrinsics
from door_contract.vocabulary import Side
from door_detection.options import DetectionOptions
from door_detection.plane import Plane, pixel_rays, sample_depth

__all__ = ["DoorAxes", "fused_standoff", "locate_grasp"]


@dataclass(frozen=True)
class DoorAxes:
    """Orthonormal door-plane axes in the optical frame: ``hinge`` (horizontal, towards
    the hinge), ``up`` and the ``normal`` (towards the camera); ``offset`` = n·p0."""

    hinge: np.ndarray
    up: np.ndarray
    normal: np.ndarray
    offset: float

    @classmethod
    def of(cls, plane: Plane, up: np.ndarray, hinge_side: Side) -> DoorAxes:
        """Axes from the plane, an approximate up (made orthogonal to n) and the hinge side
        (the hinge axis points to the hinge's side of the image: image x runs to the right,
        the robot's -y, so its sign is ``-hinge_side.sign``)."""
        normal = plane.normal
        e_up = up - float(up @ normal) * normal
        e_up = e_up / np.linalg.norm(e_up)
        e_hinge = np.cross(e_up, normal)
        if np.sign(e_hinge[0]) != -hinge_side.sign:
            e_hinge = -e_hinge
        return cls(e_hinge, e_up, normal, float(plane.point @ normal))

    def point(self, a: float, b: float, standoff: float) -> np.ndarray:
        """The optical-frame point with door coordinates (a, b) at ``standoff``."""
        return a * self.hinge + b * self.up + (self.offset + standoff) * self.normal


@dataclass(frozen=True)
class _Blob:
    """A handle's pixels, their rays' door coordinates (a, b) at stand-off ``s0``."""

    cols: np.ndarray
    rows: np.ndarray
    a: np.ndarray
    b: np.ndarray
    s0: float
    pixel: float


def locate_grasp(cols: np.ndarray, rows: np.ndarray, depth: np.ndarray, intrinsics: CameraIntrinsics,
                 plane: Plane, up: np.ndarray, hinge_side: Side,
                 options: DetectionOptions) -> np.ndarray | None:
    """The grasp point (3,) in the optical frame of the handle pixels (cols, rows), or
    None when no pixel's ray meets the plane in front of the camera.

    ``plane`` must face the camera; ``up`` is the door's approximate up; ``hinge_side``
    tells which way the lever points (levers point towards the hinge).
    """
    axes = DoorAxes.of(plane, up, hinge_side)
    s0 = fused_standoff(_standoffs(cols, rows, depth, intrinsics, plane), options)
    face = _rectify(cols, rows, intrinsics, plane, axes, 0.0)
    if face.a.size == 0:
        return None
    columns = _column_heights(face)
    if columns is None or _elongation(face, columns) < options.lever_min_elongation:
        centre = _rectify(cols, rows, intrinsics, plane, axes, s0)
        return axes.point(float(centre.a.mean()), float(centre.b.mean()), s0)
    return _lever_grasp(face, columns, depth, intrinsics, plane, axes, s0, options)


def fused_standoff(standoffs: np.ndarray, options: DetectionOptions, segmentation_sigma: float = 0.0) -> float:
    """MAP stand-off of a handle surface from its pixels' distances to the door plane.

    The measurement is the median m of the N distances, with standard error
    σ_m = 1.2533·σ̂/√N (σ̂ = 1.4826·MAD, the depth noise; 1.2533 = √(π/2), the median's
    efficiency).  It is fused with the prior N(µ_p, σ_p²) of handle stand-offs
    (``handle_standoff_prior``, ``handle_standoff_prior_sigma``):
    s = (m/σ_m² + µ_p/σ_p²) / (1/σ_m² + 1/σ_p²). ``segmentation_sigma`` adds, in quadrature, the
    error of pixels assigned to the wrong part (see :func:`_lever_grasp`).  With good depth (σ_m ≈ 1 mm) the
    measurement decides; at 4 m with stereo noise σ ≈ 8 cm and ~50 handle pixels
    (σ_m ≈ 1.4 cm) the prior halves the error.  Clipped to [0, max_handle_standoff].
    """
    if standoffs.size == 0:
        return float(np.clip(options.handle_standoff_prior, 0.0, options.max_handle_standoff))
    median = float(np.median(standoffs))
    spread = 1.4826 * float(np.median(np.abs(standoffs - median)))
    error = max(float(np.hypot(1.2533 * spread / np.sqrt(standoffs.size), segmentation_sigma)), 1e-4)
    prior = options.handle_standoff_prior_sigma
    if prior <= 0.0:
        fused = median
    else:
        weights = (1.0 / error ** 2, 1.0 / prior ** 2)
        fused = (median * weights[0] + options.handle_standoff_prior * weights[1]) / sum(weights)
    return float(np.clip(fused, 0.0, options.max_handle_standoff))


def _standoffs(cols: np.ndarray, rows: np.ndarray, depth: np.ndarray, intrinsics: CameraIntrinsics,
               plane: Plane) -> np.ndarray:
    return plane.signed_distance(sample_depth(depth, intrinsics, cols, rows))


def _rectify(cols: np.ndarray, rows: np.ndarray, intrinsics: CameraIntrinsics, plane: Plane,
             axes: DoorAxes, standoff: float) -> _Blob:
    on_plane = plane.offset(standoff).intersect_rays(pixel_rays(intrinsics, cols, rows))
    hit = np.all(np.isfinite(on_plane), axis=1) & (on_plane[:, 2] > 0)
    on_plane, cols, rows = on_plane[hit], cols[hit], rows[hit]
    pixel = float(np.median(on_plane[:, 2])) / intrinsics.fx if hit.any() else 1.0
    return _Blob(cols, rows, on_plane @ axes.hinge, on_plane @ axes.up, standoff, pixel)


@dataclass(frozen=True)
class _Columns:
    """Per-pixel column index along a, per column its height (m); the bar's height."""

    index: np.ndarray
    heights: np.ndarray
    bar: float

    def rose(self) -> np.ndarray:
        """Per-pixel mask of the rose: columns ≥ (bar + tallest)/2 when the tallest is
        ≥ 1.6 bars (else no rose)."""
        tallest = float(self.heights.max())
        if tallest < 1.6 * self.bar:
            return np.zeros(self.index.shape, dtype=bool)
        mask: np.ndarray = (self.heights >= 0.5 * (self.bar + tallest))[self.index]
        return mask


def _column_heights(blob: _Blob) -> _Columns | None:
    if blob.a.size < 3:
        return None
    index = np.floor((blob.a - blob.a.min()) / blob.pixel).astype(np.intp)
    count = int(index.max()) + 1
    top, bottom = np.full(count, -np.inf), np.full(count, np.inf)
    np.maximum.at(top, index, blob.b)
    np.minimum.at(bottom, index, blob.b)
    heights = np.where(np.isfinite(top), top - bottom + blob.pixel, 0.0)
    return _Columns(index, heights, float(np.median(heights[heights > 0])))


def _elongation(blob: _Blob, columns: _Columns) -> float:
    return (float(blob.a.max() - blob.a.min()) + blob.pixel) / max(columns.bar, 1e-9)


def _lever_grasp(face: _Blob, columns: _Columns, depth: np.ndarray, intrinsics: CameraIntrinsics,
                 plane: Plane, axes: DoorAxes, s0: float, options: DetectionOptions) -> np.ndarray:
    """Grasp point of a bar-on-rose lever.

    ``face`` is the blob rectified on the door face (stand-off 0), where the rose lies,
    so the rose columns and the axis (middle of the rose's extent along a) are free of
    parallax.  The bar pixels (hinge-ward of the rose) are rectified again at the bar's
    own stand-off (median of their depth) for the tip and the bar's centre line.

    A bar only a few pixels high is not told from the rose and the door beside it at its
    rims: a pixel in h = bar/pixel rows misassigned moves the median by up to a stand-off,
    so the bar's stand-off carries a segmentation error µ_p·min(1/h, 1) besides the noise.
    At 4 m with a 416 px focal length (h ≈ 2.5) the prior then dominates: the measured
    median, pulled to 3.9 cm by the rose for a whole view, had put the grasp 1.9 cm behind
    the lever; a 6-px bar keeps most of the measurement's weight.
    """
    on_rose = columns.rose()
    bar_mask = face.a > face.a[on_rose].max() if on_rose.any() else np.ones_like(on_rose)
    if bar_mask.sum() < 3:
        bar_mask = ~on_rose if (~on_rose).sum() >= 3 else np.ones_like(on_rose)
    bar_standoffs = _standoffs(face.cols[bar_mask], face.rows[bar_mask], depth, intrinsics, plane)
    unresolved = options.handle_standoff_prior * min(face.pixel / max(columns.bar, 1e-9), 1.0)
    s_bar = fused_standoff(bar_standoffs, options, unresolved) if bar_standoffs.size else s0
    bar = _rectify(face.cols[bar_mask], face.rows[bar_mask], intrinsics, plane, axes, s_bar)
    if bar.a.size == 0:
        bar = face
    if on_rose.any():
        axis = 0.5 * (float(face.a[on_rose].min()) + float(face.a[on_rose].max()))
    else:
        axis = float(bar.a.min()) - bar.pixel / 2 + columns.bar / 2
    tip = float(bar.a.max()) + bar.pixel / 2
    length = max(tip - axis - columns.bar / 2, 0.0)
    half_section = min(columns.bar / 2, options.lever_max_half_section)
    return axes.point(axis + options.lever_grasp_fraction * length, float(np.median(bar.b)),
                      max(s_bar - half_section, 0.0))
