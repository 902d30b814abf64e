"""Operator-aided door detection from a scribble on the handle ([Banerjee 2015] Sec. III-B).

"The operator scribbles on the door handle and based on the knowledge of where the door
handle is, i.e. on the right or on the left of the door, points offset on the side of
the seeded point is sampled and a plane is fit to appropriate those points. This
provides the handle point (operator seed) and the normal to the door."

Here:

1. the scribble (a pixel polygon, or a polyline of ≥ 1 points) must lie inside the
   image; its pixels (grown by ``scribble_dilation``) form the seed mask;
2. the metric scale at the seed is z_s = median valid depth around it, so regions given
   in metres become pixel boxes (w_px = w·f/z_s);
3. a box ``scribble_region_width`` × ``scribble_region_height`` is sampled on the door
   side of the scribble (towards the hinge; both sides when the side is unknown), minus
   the scribble's bounding box grown by ``scribble_exclusion``, so the handle itself is
   not fitted;
4. Open3D ``segment_plane`` (RANSAC) fits the door plane, refined by gated least
   squares over all the region's points (:func:`~door_detection.plane.refine_plane`:
   refining over the RANSAC inliers only would keep the RANSAC plane's tilt under
   noise comparable to the 5 cm threshold); the normal is turned towards the camera;
5. inside the seed mask, the pixels whose colour is not the sampled door's (µ ± kσ, the
   rule of Sec. III-A) are the handle, grown to the connected handle-coloured pixels
   around it; its grasp point is computed as in automatic mode
   (:func:`~door_detection.grasp.locate_grasp`).
"""

from __future__ import annotations

import time

import cv2
import numpy as np
import open3d

from door_contract.converters.camera_info import CameraIntrinsics
from door_contract.vocabulary import DetectionMode, Side
from door_detection.automatic import UNEXPECTED_ERRORS
from door_detection.errors import InputError
from door_detection.estimate import DetectedDoor, DetectionOutcome, DetectionResult
from door_detection.grasp import locate_grasp
from door_detection.handle import ColourStats, HandleBlob, colour_stats, grow_blob
from door_detection.options import DetectionOptions
from door_detection.plane import Plane, refine_plane, sample_depth
from door_detection.preprocessing import DepthError, RgbdFrame, validate_frame

__all__ = ["detect_from_scribble"]

NO_CORNERS = np.full((4, 3), np.nan)
PROUD_OF_DOOR = 0.025
"""A handle pixel stands at least this far in front of the door plane (m); the frame and
the door itself do not (a lever's bar stands 5–8 cm proud)."""


def detect_from_scribble(rgb: np.ndarray, depth: np.ndarray, intrinsics: CameraIntrinsics,
                         scribble: np.ndarray, options: DetectionOptions | None = None,
                         hinge_side: Side | None = None, up: np.ndarray | None = None) -> DetectionResult:
    """Handle point and door normal from an operator's scribble; never raises on bad input.

    ``scribble``: (N, 2) pixel coordinates (u, v) on ``rgb`` (N ≥ 1; N ≥ 3 is a polygon,
    fewer a polyline); ``hinge_side``: where the hinge is in the image (the door side of
    the handle), or None to sample both sides and guess the hinge side from colour;
    ``up``: the world's up direction in the optical frame (from tf: the head's pitch
    and roll), or None for the image's up (−y, exact only for a level head).  The lever
    model measures along the door's horizontal, so a pitched head needs ``up``.
    """
    opts = options if options is not None else DetectionOptions()
    start = time.perf_counter()
    try:
        frame = validate_frame(rgb, depth, intrinsics, opts)
        estimate = _detect(frame, _validate_scribble(scribble, frame), opts, hinge_side,
                           _validate_up(up))
    except DepthError as error:
        return DetectionResult(DetectionOutcome.NO_VALID_DEPTH, None, str(error),
                               time.perf_counter() - start)
    except InputError as error:
        return DetectionResult(DetectionOutcome.BAD_INPUT, None, str(error), time.perf_counter() - start)
    except _PlaneFailure as failure:
        return DetectionResult(DetectionOutcome.PLANE_FIT_FAILED, None, str(failure),
                               time.perf_counter() - start)
    except UNEXPECTED_ERRORS as error:  # a bug must not take the node down (DESIGN.md)
        return DetectionResult(DetectionOutcome.INTERNAL_ERROR, None, f"{type(error).__name__}: {error}",
                               time.perf_counter() - start)
    return DetectionResult(DetectionOutcome.DETECTED, estimate, "", time.perf_counter() - start)


class _PlaneFailure(Exception):
    """The sampled region holds no plane."""


def _validate_scribble(scribble: np.ndarray, frame: RgbdFrame) -> np.ndarray:
    """(N, 2) finite pixel coordinates inside the image, else :class:`InputError`."""
    points = np.asarray(scribble, dtype=float)
    if points.ndim != 2 or points.shape[1] != 2 or len(points) == 0:
        raise InputError(f"scribble must be an (N, 2) array of pixels with N >= 1, got shape {points.shape}")
    if not np.all(np.isfinite(points)):
        raise InputError("scribble contains NaN or infinity")
    outside = (points[:, 0] < 0) | (points[:, 0] > frame.width - 1) | \
              (points[:, 1] < 0) | (points[:, 1] > frame.height - 1)
    if outside.any():
        raise InputError(f"{int(outside.sum())} scribble point(s) lie outside the "
                         f"{frame.width}×{frame.height} image")
    return points


def _validate_up(up: np.ndarray | None) -> np.ndarray:
    """A unit up vector (default −y of the optical frame), else :class:`InputError`."""
    if up is None:
        return np.array([0.0, -1.0, 0.0])
    vector = np.asarray(up, dtype=float)
    if vector.shape != (3,) or not np.all(np.isfinite(vector)) or np.linalg.norm(vector) < 1e-9:
        raise InputError(f"up must be a finite non-zero 3-vector, got {up!r}")
    unit: np.ndarray = vector / np.linalg.norm(vector)
    return unit


def _seed_mask(points: np.ndarray, shape: tuple[int, int], dilation: int) -> np.ndarray:
    """The scribble's pixels: filled polygon (N ≥ 3) or polyline, grown by ``dilation`` px."""
    mask = np.zeros(shape, dtype=np.uint8)
    pixels = np.rint(points).astype(np.int32).reshape(-1, 1, 2)
    if len(points) >= 3:
        cv2.fillPoly(mask, [pixels], 1)
    cv2.polylines(mask, [pixels], isClosed=len(points) >= 3, color=1, thickness=1)
    if dilation > 0:
        kernel = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (2 * dilation + 1, 2 * dilation + 1))
        return np.asarray(cv2.dilate(mask, kernel)).astype(bool)
    return mask.astype(bool)


def _detect(frame: RgbdFrame, points: np.ndarray, options: DetectionOptions,
            hinge_side: Side | None, up: np.ndarray) -> DetectedDoor:
    seed = _seed_mask(points, frame.depth.shape, options.scribble_dilation)
    drawn = _seed_mask(points, frame.depth.shape, 0)
    rows, cols = np.nonzero(seed)
    box = (int(cols.min()), int(rows.min()), int(cols.max()), int(rows.max()))
    z_seed = _seed_depth(frame, box, options)
    pixels_per_metre = frame.intrinsics.fx / z_seed
    region = _region_mask(frame.depth.shape, box, pixels_per_metre, options, hinge_side)
    plane, noise = _fit_region_plane(frame, region, options)
    stats = colour_stats(frame.rgb[region & np.isfinite(frame.depth)])
    side = hinge_side if hinge_side is not None else _guess_hinge_side(frame, box, pixels_per_metre,
                                                                        stats, options)
    handle = _segment_handle(frame, (seed, drawn), box, stats, side, plane, noise, options)
    position = locate_grasp(handle.cols, handle.rows, frame.depth, frame.intrinsics, plane, up, side,
                            options)
    if position is None:
        raise _PlaneFailure("the scribble's rays miss the fitted plane")
    return DetectedDoor(position, plane.normal, side, float("nan"), NO_CORNERS,
                        _confidence(frame, region, plane, options), DetectionMode.OPERATOR, 1, up)


def _segment_handle(frame: RgbdFrame, masks: tuple[np.ndarray, np.ndarray], box: tuple[int, int, int, int],
                    door: ColourStats, hinge_side: Side, plane: Plane, noise: float,
                    options: DetectionOptions) -> HandleBlob:
    """The handle's pixels: inside the seed mask (``masks``: the grown scribble, and the
    scribble as drawn), those not of the door's colour, in connected parts that touch the
    drawn scribble, and not on the door plane (the whole seed if fewer than 3 remain), grown
    to the connected handle-coloured pixels around (an operator marks the lever; its rose
    may lie outside the scribble).

    "Touch the drawn scribble": the grown seed may reach past a latch-side handle onto the
    jamb, whose face is neither door-coloured nor, under stereo noise, told from the door
    plane; at 4 m that column of jamb pixels joined the blob and moved the grasp 3.2 cm
    towards the latch. The lever the operator drew around is the part that touches.

    "Not on the plane": a scribble near the latch edge also covers the frame, which is
    neither door-coloured nor proud of the door.  Pixels closer than
    ``PROUD_OF_DOOR`` to the plane are dropped when the depth noise ``noise`` (σ of the
    door points around the plane) allows telling them apart (3σ < ``PROUD_OF_DOOR``);
    pixels without depth are kept.
    """
    x0, y0, x1, y1 = box
    crop = frame.rgb[y0: y1 + 1, x0: x1 + 1]
    inside = masks[0][y0: y1 + 1, x0: x1 + 1]
    handle = _touching(inside & ~door.matches(crop, options), masks[1][y0: y1 + 1, x0: x1 + 1])
    if handle.sum() < 3:
        handle = inside
    rows, cols = np.nonzero(handle)
    proud = _proud_of_door(frame, rows + y0, cols + x0, plane)
    if 3.0 * noise < PROUD_OF_DOOR and proud.sum() >= 3:
        rows, cols = rows[proud], cols[proud]
    return grow_blob(frame.rgb, HandleBlob(rows + y0, cols + x0, hinge_side.other), door, options)


def _touching(mask: np.ndarray, drawn: np.ndarray) -> np.ndarray:
    """The 8-connected parts of ``mask`` that overlap ``drawn`` (all of ``mask`` if none does)."""
    _, labels = cv2.connectedComponents(mask.astype(np.uint8), connectivity=8)
    touched = np.unique(labels[drawn & mask])
    return np.isin(labels, touched[touched > 0]) if touched.size else mask


def _proud_of_door(frame: RgbdFrame, rows: np.ndarray, cols: np.ndarray, plane: Plane) -> np.ndarray:
    """Mask of the pixels that may belong to a handle: no depth, or at least
    ``PROUD_OF_DOOR`` in front of the plane."""
    z = frame.depth[rows, cols]
    valid = np.isfinite(z)
    points = frame.intrinsics.back_project(cols[valid].astype(float), rows[valid].astype(float), z[valid])
    distance = np.full(rows.shape, np.inf)
    distance[valid] = plane.signed_distance(points)
    return distance >= PROUD_OF_DOOR


def _seed_depth(frame: RgbdFrame, box: tuple[int, int, int, int], options: DetectionOptions) -> float:
    """Median valid depth in growing windows around the scribble's box (m)."""
    x0, y0, x1, y1 = box
    for grow in (10, 40, 120):
        window = frame.depth[max(y0 - grow, 0): y1 + grow + 1, max(x0 - grow, 0): x1 + grow + 1]
        valid = window[np.isfinite(window)]
        if valid.size >= options.min_region_points:
            return float(np.median(valid))
    raise DepthError("no valid depth around the scribble")


def _region_mask(shape: tuple[int, int], box: tuple[int, int, int, int], pixels_per_metre: float,
                 options: DetectionOptions, hinge_side: Side | None) -> np.ndarray:
    """Box on the door side of the scribble, minus the scribble's grown bounding box."""
    height, width = shape
    x0, y0, x1, y1 = box
    reach = int(round(options.scribble_region_width * pixels_per_metre))
    half_height = int(round(options.scribble_region_height * pixels_per_metre / 2))
    exclusion = int(round(options.scribble_exclusion * pixels_per_metre))
    left = x0 - reach if hinge_side is not Side.RIGHT else x0
    right = x1 + reach if hinge_side is not Side.LEFT else x1
    centre = (y0 + y1) // 2
    mask = np.zeros(shape, dtype=bool)
    mask[max(centre - half_height, 0): min(centre + half_height + 1, height),
         max(left, 0): min(right + 1, width)] = True
    mask[max(y0 - exclusion, 0): y1 + exclusion + 1, max(x0 - exclusion, 0): x1 + exclusion + 1] = False
    return mask


def _fit_region_plane(frame: RgbdFrame, region: np.ndarray, options: DetectionOptions) -> tuple[Plane, float]:
    """Open3D RANSAC plane (Sec. III-B) over the region's valid points, refined by robust
    least squares, normal towards the camera; and the depth noise σ about it (MAD)."""
    rows, cols = np.nonzero(region)
    stride = max(len(rows) // options.plane_max_points, 1)
    points = sample_depth(frame.depth, frame.intrinsics, cols[::stride], rows[::stride])
    wanted = max(options.min_region_points, options.min_valid_fraction * len(rows[::stride]))
    if len(points) < wanted:
        raise DepthError(f"only {len(points)} of {len(rows[::stride])} samples beside the scribble have "
                         f"valid depth (need {int(np.ceil(wanted))})")
    cloud = open3d.geometry.PointCloud(open3d.utility.Vector3dVector(points))
    open3d.utility.random.seed(options.random_seed)
    model, inliers = cloud.segment_plane(options.plane_inlier_distance, 3,
                                         options.operator_ransac_iterations)
    if len(inliers) < max(3, options.min_region_points // 2):
        raise _PlaneFailure(f"the plane explains only {len(inliers)} of {len(points)} points")
    normal = np.asarray(model[:3], dtype=float)
    norm = float(np.linalg.norm(normal))
    initial = Plane(-float(model[3]) / norm * normal / norm, normal / norm).facing(np.zeros(3))
    plane, _ = refine_plane(points, initial, options.plane_inlier_distance)
    plane = plane.facing(np.zeros(3))
    residual = np.abs(plane.signed_distance(points))
    return plane, 1.4826 * float(np.median(residual))


def _confidence(frame: RgbdFrame, region: np.ndarray, plane: Plane, options: DetectionOptions) -> float:
    """Fraction of the region's valid points within ``plane_inlier_distance`` of the plane."""
    rows, cols = np.nonzero(region)
    stride = max(len(rows) // options.plane_max_points, 1)
    points = sample_depth(frame.depth, frame.intrinsics, cols[::stride], rows[::stride])
    return float(np.mean(np.abs(plane.signed_distance(points)) <= options.plane_inlier_distance))


def _guess_hinge_side(frame: RgbdFrame, box: tuple[int, int, int, int], pixels_per_metre: float,
                      stats: ColourStats, options: DetectionOptions) -> Side:
    """The side whose strip beside the handle is more door-coloured is the door (hinge) side.

    The handle sits a few centimetres from the latch edge, so a strip 10–25 cm away on the
    latch side shows the frame or wall, on the hinge side the door.
    """
    x0, y0, x1, y1 = box
    near, far = (int(round(d * pixels_per_metre)) for d in (0.10, 0.25))
    rows = slice(max(y0, 0), y1 + 1)
    fractions = {}
    for side, (a, b) in ((Side.LEFT, (x0 - far, x0 - near)), (Side.RIGHT, (x1 + near, x1 + far))):
        strip = frame.rgb[rows, max(a, 0): max(min(b, frame.width), 0)]
        fractions[side] = float(stats.matches(strip, options).mean()) if strip.size else 0.0
    return Side.LEFT if fractions[Side.LEFT] >= fractions[Side.RIGHT] else Side.RIGHT
