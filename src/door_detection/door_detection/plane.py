"""Planes and 3-D lines: fits, RANSAC, ray intersection, depth sampling.

All points are in the camera optical frame (metres); rays start at the camera centre.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from door_contract.converters.camera_info import CameraIntrinsics

__all__ = ["Line3D", "Plane", "depth_noise", "fit_plane", "pixel_rays", "ransac_line", "refine_plane", "sample_depth"]


@dataclass(frozen=True)
class Plane:
    """The plane n·(p − point) = 0 with unit normal n (oriented by the caller)."""

    point: np.ndarray
    normal: np.ndarray

    def signed_distance(self, points: np.ndarray) -> np.ndarray:
        """(points − point)·n for an (N, 3) array: > 0 on the side n points to."""
        distance: np.ndarray = (np.asarray(points) - self.point) @ self.normal
        return distance

    def facing(self, origin: np.ndarray) -> Plane:
        """The same plane with n pointing to the side ``origin`` is on."""
        if float((np.asarray(origin) - self.point) @ self.normal) < 0.0:
            return Plane(self.point, -self.normal)
        return self

    def offset(self, distance: float) -> Plane:
        """The parallel plane ``distance`` along n."""
        return Plane(self.point + distance * self.normal, self.normal)

    def intersect_rays(self, directions: np.ndarray) -> np.ndarray:
        """Points where rays from the origin along ``directions`` (N, 3) meet the plane.

        t = (n·p0)/(n·d); rays parallel to the plane give NaN.
        """
        d = np.atleast_2d(np.asarray(directions, dtype=float))
        denominator = d @ self.normal
        with np.errstate(divide="ignore", invalid="ignore"):
            t = float(self.point @ self.normal) / denominator
        t = np.where(np.abs(denominator) > 1e-12, t, np.nan)
        points: np.ndarray = d * t[:, None]
        return points


@dataclass(frozen=True)
class Line3D:
    """A 3-D line through ``point`` along unit ``direction`` fitted to ``inliers`` of
    ``samples`` valid points."""

    point: np.ndarray
    direction: np.ndarray
    inliers: int
    samples: int

    @property
    def inlier_fraction(self) -> float:
        return self.inliers / max(self.samples, 1)

    def distance(self, points: np.ndarray) -> np.ndarray:
        """Perpendicular distance of (N, 3) points to the line."""
        offset = np.asarray(points) - self.point
        along = offset @ self.direction
        distance: np.ndarray = np.linalg.norm(offset - along[:, None] * self.direction, axis=1)
        return distance


def pixel_rays(intrinsics: CameraIntrinsics, u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Ray directions (N, 3) with z = 1 through pixels (u, v)."""
    return intrinsics.back_project(np.asarray(u, float), np.asarray(v, float), np.ones(np.shape(u)))


def sample_depth(depth: np.ndarray, intrinsics: CameraIntrinsics, u: np.ndarray,
                 v: np.ndarray) -> np.ndarray:
    """Back-projected points (M, 3) of the pixels (u, v) (rounded) with valid depth.

    Pixels outside the image or with NaN depth are dropped.
    """
    col = np.rint(np.asarray(u, float)).astype(np.intp)
    row = np.rint(np.asarray(v, float)).astype(np.intp)
    inside = (col >= 0) & (col < depth.shape[1]) & (row >= 0) & (row < depth.shape[0])
    col, row = col[inside], row[inside]
    z = depth[row, col]
    valid = np.isfinite(z)
    return intrinsics.back_project(col[valid].astype(float), row[valid].astype(float), z[valid])


def depth_noise(points: np.ndarray) -> float:
    """Robust σ of the depth noise along an ordered profile of a smooth surface.

    Second differences cancel any linear depth trend (a slanted door), leaving
    z_{i+1} − 2z_i + z_{i−1} ≈ N(0, 6σ²): σ̂ = 1.4826·median|Δ²z|/√6 (MAD estimator;
    steps such as a handle are outliers).
    """
    if len(points) < 4:
        return 0.0
    return float(1.4826 * np.median(np.abs(np.diff(points[:, 2], n=2))) / np.sqrt(6.0))


def fit_plane(points: np.ndarray) -> Plane:
    """Least-squares plane: centroid and the singular vector of the smallest singular value."""
    centroid = points.mean(axis=0)
    _, _, vt = np.linalg.svd(points - centroid, full_matrices=False)
    return Plane(centroid, vt[2])


def refine_plane(points: np.ndarray, initial: Plane, threshold: float,
                 rounds: int = 3) -> tuple[Plane, float]:
    """Robust least-squares plane in inverse-depth space, starting from ``initial``.

    A plane n·p = d seen through the pinhole p = z·(x', y', 1) satisfies
    1/z = a·x' + b·y' + c with (a, b, c) = n/d: inverse depth is *affine* in the
    normalised image coordinates.  Stereo depth noise is constant in disparity (∝ 1/z;
    σ_z = k·z² means σ_{1/z} = k), so ordinary least squares of w = 1/z on (x', y', 1) is
    the unbiased, optimal fit, whereas a 3-D orthogonal fit is biased when the noise runs
    along oblique rays.  Round r keeps the points whose residual is below
    max(threshold/z²/2^r, 2.5·σ̂_w) (σ̂_w: MAD of the residuals) and refits.  The
    orientation of ``initial.normal`` is kept.  Returns the plane and the fraction of
    points within ``threshold`` (metres, along the normal) of it.
    """
    z = points[:, 2]
    ok = z > 0
    x, y, w, z = points[ok, 0] / z[ok], points[ok, 1] / z[ok], 1.0 / z[ok], z[ok]
    design = np.column_stack([x, y, np.ones_like(x)])
    coefficients = _inverse_depth_coefficients(initial)
    for r in range(rounds):
        residual = np.abs(w - design @ coefficients)
        sigma = 1.4826 * float(np.median(residual))
        keep = residual <= np.maximum(threshold / z ** 2 / 2 ** r, 2.5 * sigma)
        if keep.sum() < 3:
            break
        coefficients = np.linalg.lstsq(design[keep], w[keep], rcond=None)[0]
    plane = _plane_of_coefficients(coefficients, initial)
    fraction = float(np.mean(np.abs(plane.signed_distance(points)) <= threshold))
    return plane, fraction


def _inverse_depth_coefficients(plane: Plane) -> np.ndarray:
    """(a, b, c) = n/d of the plane n·p = d (d ≠ 0: the plane misses the camera centre)."""
    d = float(plane.normal @ plane.point)
    return plane.normal / d if abs(d) > 1e-9 else plane.normal * 1e9


def _plane_of_coefficients(coefficients: np.ndarray, like: Plane) -> Plane:
    """The plane 1/z = (a, b, c)·(x', y', 1) with its normal on ``like``'s side."""
    norm = float(np.linalg.norm(coefficients))
    normal = coefficients / norm
    point = normal / norm                       # n·p = 1/|m| = d
    if normal @ like.normal < 0:
        normal = -normal
    return Plane(point, normal)


def ransac_line(points: np.ndarray, threshold: float, iterations: int,
                rng: np.random.Generator) -> Line3D | None:
    """RANSAC 3-D line (Sec. III-A), all hypotheses scored at once.

    ``iterations`` point pairs define candidate lines; the one with most points within
    ``threshold`` wins and is refitted by PCA (principal direction of its inliers).
    None with fewer than two points.
    """
    n = len(points)
    if n < 2:
        return None
    a, b = rng.integers(0, n, size=(2, iterations))
    keep = a != b
    a, b = a[keep], b[keep]
    if len(a) == 0:
        return None
    origins = points[a]
    dirs = points[b] - origins
    dirs /= np.maximum(np.linalg.norm(dirs, axis=1, keepdims=True), 1e-12)
    offsets = points[None, :, :] - origins[:, None, :]                    # (K, N, 3)
    along = np.einsum("knc,kc->kn", offsets, dirs)
    dist2 = np.einsum("knc,knc->kn", offsets, offsets) - along ** 2
    counts = (dist2 <= threshold ** 2).sum(axis=1)
    best = int(np.argmax(counts))
    inliers = points[dist2[best] <= threshold ** 2]
    centroid = inliers.mean(axis=0)
    _, _, vt = np.linalg.svd(inliers - centroid, full_matrices=False)
    line = Line3D(centroid, vt[0], 0, n)
    return Line3D(centroid, vt[0], int((line.distance(points) <= threshold).sum()), n)
