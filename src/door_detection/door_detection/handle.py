"""Handle segmentation by colour statistics ([Banerjee 2015] Sec. III-A, used by III-B too).

The paper's rule (Sec. III-A, second phase): with µ and σ the mean and standard
deviation of the door's pixels, door pixels are those within [µ − σ, µ + σ] ("marked
white" by connected-component growth); on the handle side, away from the door's central
part, the non-white region above an area threshold is the handle.  Here the test is per
colour channel (the paper used grey; colour separates e.g. a brass handle on a wooden
door of equal brightness), σ has a floor ``handle_min_sigma`` (an evenly painted door has
σ ≈ 0), and the largest admissible blob wins (the paper scanned from the bottom).  The
side strips are measured in metric fractions of the door (perspective-corrected), blobs
crossing the search band or taller than wide are rejected (frames, edges, shadows), and
the blob is finally grown to the connected pixels of its own colour (a handle seen at an
angle projects past the door edge).

The 3-D grasp point is computed from the blob by :mod:`~door_detection.grasp`.
"""

from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np

from door_contract.vocabulary import Side
from door_detection.options import DetectionOptions

__all__ = ["ColourStats", "HandleBlob", "colour_stats", "find_handle", "grow_blob", "robust_colour_stats",
           "touches_border"]

HANDLE_GROW_SIGMAS = 2.5
"""A pixel joins a handle blob within this many of the blob's own σ (its faces are shaded
differently, so the door's 1σ would be too strict)."""
HANDLE_SEARCH_WIDTH = 200.0
"""Doors wider than this (px) are searched for the handle in a shrunk crop."""
HANDLE_GROW_LIMIT = 3.0
"""Growing may multiply a blob's area by at most this (a rose next to a lever: ~2)."""


@dataclass(frozen=True)
class ColourStats:
    """Per-channel mean µ (3,) and standard deviation σ (3,) of door pixels (0..255)."""

    mean: np.ndarray
    sigma: np.ndarray

    def matches(self, pixels: np.ndarray, options: DetectionOptions, scale: float | None = None) -> np.ndarray:
        """Mask of pixels (…, 3) within k·max(σ, σ_min) of µ in every channel
        (k = ``scale``, default ``handle_sigma_scale``)."""
        k = options.handle_sigma_scale if scale is None else scale
        tolerance = k * np.maximum(self.sigma, options.handle_min_sigma)
        mask: np.ndarray = np.all(np.abs(pixels.astype(np.float32) - self.mean.astype(np.float32))
                                  <= tolerance.astype(np.float32), axis=-1)
        return mask


@dataclass(frozen=True)
class HandleBlob:
    """A handle in the image: its pixels (full-resolution ``rows``, ``cols``), area (px),
    centroid (u, v) and the side of the door it is on (as seen in the image)."""

    rows: np.ndarray
    cols: np.ndarray
    side: Side

    @property
    def area(self) -> int:
        return int(self.rows.size)

    @property
    def centroid(self) -> tuple[float, float]:
        return float(self.cols.mean()), float(self.rows.mean())


def touches_border(blob: HandleBlob, shape: tuple[int, ...]) -> bool:
    """The blob reaches the image's outermost rows or columns: part of the handle may lie
    beyond them, so its extent (the lever's tip, hence the grasp point) is unknown."""
    height, width = shape[:2]
    return bool(blob.cols.min() <= 0 or blob.rows.min() <= 0 or blob.cols.max() >= width - 1
                or blob.rows.max() >= height - 1)


def colour_stats(pixels: np.ndarray) -> ColourStats:
    """µ and σ of an (N, 3) set of pixels."""
    values = pixels.reshape(-1, 3).astype(np.float64)
    return ColourStats(values.mean(axis=0), values.std(axis=0))


def robust_colour_stats(pixels: np.ndarray) -> ColourStats:
    """Median and MAD-σ (1.4826·median|x − median|) of an (N, 3) set of pixels: the
    colour of the majority even when a minority (frame, shadow) is mixed in."""
    values = pixels.reshape(-1, 3).astype(np.float64)
    median = np.median(values, axis=0)
    return ColourStats(median, 1.4826 * np.median(np.abs(values - median), axis=0))


@dataclass(frozen=True)
class _DoorCrop:
    """The door's bounding box (x0, y0) in the image and, per crop pixel, the fraction
    across the door from its left edge (t) and up from its bottom edge (h)."""

    x0: int
    y0: int
    t: np.ndarray
    h: np.ndarray
    top_visible: bool
    bottom_visible: bool


def _door_crop(corners: np.ndarray, shape: tuple[int, int], depth_ratio: float) -> _DoorCrop | None:
    """Fractional door coordinates over the crop of the quadrilateral (BL, BR, TR, TL).

    Along a row, the image fraction τ between the edges is not the metric fraction t
    across a door seen at an angle: for the segment (1 − t)P_L + tP_R with depths Z_L,
    Z_R, τ = tZ_R/((1 − t)Z_L + tZ_R), so t = τρ/(τρ + 1 − τ) with ρ = Z_L/Z_R.
    """
    height, width = shape
    x0 = int(max(np.floor(corners[:, 0].min()), 0))
    x1 = int(min(np.ceil(corners[:, 0].max()) + 1, width))
    y0 = int(max(np.floor(corners[:, 1].min()), 0))
    y1 = int(min(np.ceil(corners[:, 1].max()) + 1, height))
    if x1 - x0 < 3 or y1 - y0 < 3:
        return None
    top, bottom = float(corners[3, 1]), float(corners[0, 1])
    ys = np.arange(y0, y1, dtype=np.float32)[:, None]
    fraction = (ys - top) / max(bottom - top, 1e-6)
    xl = corners[3, 0] + fraction * (corners[0, 0] - corners[3, 0])
    xr = corners[2, 0] + fraction * (corners[1, 0] - corners[2, 0])
    xs = np.arange(x0, x1, dtype=np.float32)[None, :]
    tau = (xs - xl) / np.maximum(xr - xl, 1e-6)
    t = tau * depth_ratio / np.maximum(tau * depth_ratio + 1.0 - tau, 1e-6)
    h = np.broadcast_to(1.0 - fraction, t.shape)
    return _DoorCrop(x0, y0, t.astype(np.float32), h.astype(np.float32),
                     top > 1.0, bottom < height - 2.0)


def find_handle(rgb: np.ndarray, corners: np.ndarray, options: DetectionOptions,
                hinge_side: Side | None = None, depth_ratio: float = 1.0) -> HandleBlob | None:
    """The handle blob inside the door quadrilateral ``corners`` (4, 2) px, or None.

    ``hinge_side`` (prior knowledge, Sec. III-A) restricts the search to the other side;
    None searches both sides and keeps the larger blob.  ``depth_ratio`` = Z_left/Z_right
    of the door's edges turns image fractions across the door into metric ones.

    A door wider than ``HANDLE_SEARCH_WIDTH`` px is searched in a crop shrunk to that
    width (a near door fills the image; the handle stays tens of pixels long), and the
    blob found is then re-segmented at full resolution around its position.
    """
    scale = min(1.0, HANDLE_SEARCH_WIDTH / max(float(np.ptp(corners[:, 0])), 1.0))
    if scale >= 1.0:
        found = _search(rgb, corners, options, hinge_side, depth_ratio, 1.0)
        return None if found is None else grow_blob(rgb, found[0], found[1], options)
    height, width = rgb.shape[:2]
    x0, y0 = int(max(np.floor(corners[:, 0].min()), 0)), int(max(np.floor(corners[:, 1].min()), 0))
    x1 = int(min(np.ceil(corners[:, 0].max()) + 1, width))
    y1 = int(min(np.ceil(corners[:, 1].max()) + 1, height))
    if x1 - x0 < 3 or y1 - y0 < 3:
        return None
    small = cv2.resize(rgb[y0:y1, x0:x1], None, fx=scale, fy=scale, interpolation=cv2.INTER_AREA)
    small_corners = (corners - [x0, y0] + 0.5) * scale - 0.5
    found = _search(small, small_corners, options, hinge_side, depth_ratio, scale)
    if found is None:
        return None
    blob = _full_resolution(rgb, found[0], found[1], scale, (x0, y0), options)
    return None if blob is None else grow_blob(rgb, blob, found[1], options)


def _search(rgb: np.ndarray, corners: np.ndarray, options: DetectionOptions, hinge_side: Side | None,
            depth_ratio: float, scale: float) -> tuple[HandleBlob, ColourStats] | None:
    """Door colour statistics and the best side blob in ``rgb`` (possibly a shrunk crop)."""
    crop = _door_crop(corners, rgb.shape[:2], depth_ratio)
    if crop is None:
        return None
    pixels = rgb[crop.y0: crop.y0 + crop.t.shape[0], crop.x0: crop.x0 + crop.t.shape[1]]
    m = options.door_margin_fraction
    inner = (crop.t >= m) & (crop.t <= 1 - m) & (crop.h >= m) & (crop.h <= 1 - m)
    if inner.sum() < options.min_region_points:
        return None
    stats = colour_stats(pixels[inner][:: max(int(inner.sum()) // 20000, 1)])
    not_door = ~stats.matches(pixels, options)
    door_area = float(inner.sum())
    sides = [hinge_side.other] if hinge_side is not None else [Side.LEFT, Side.RIGHT]
    blobs = [b for b in (_side_blob(crop, not_door, side, door_area, options, scale) for side in sides)
             if b is not None]
    return (max(blobs, key=lambda b: b.area), stats) if blobs else None


def _full_resolution(rgb: np.ndarray, small: HandleBlob, door: ColourStats, scale: float,
                     offset: tuple[int, int], options: DetectionOptions) -> HandleBlob | None:
    """Re-segment a blob found at ``scale`` in the full image: the non-door connected
    components of its (grown by 1/scale) bounding box that overlap its upscaled pixels."""
    height, width = rgb.shape[:2]
    pad = int(np.ceil(1.0 / scale)) + 1

    def to_full(v: np.ndarray, o: int) -> np.ndarray:
        full: np.ndarray = (v + 0.5) / scale - 0.5 + o
        return full

    cols, rows = to_full(small.cols, offset[0]), to_full(small.rows, offset[1])
    x0, x1 = max(int(cols.min()) - pad, 0), min(int(cols.max()) + pad + 1, width)
    y0, y1 = max(int(rows.min()) - pad, 0), min(int(rows.max()) + pad + 1, height)
    mask = ~door.matches(rgb[y0:y1, x0:x1], options)
    _, labels = cv2.connectedComponents(mask.astype(np.uint8), connectivity=8)
    seeds = labels[np.clip(np.rint(rows).astype(int) - y0, 0, y1 - y0 - 1),
                   np.clip(np.rint(cols).astype(int) - x0, 0, x1 - x0 - 1)]
    keep = np.unique(seeds[seeds > 0])
    if keep.size == 0:
        return None
    found_rows, found_cols = np.nonzero(np.isin(labels, keep))
    return HandleBlob(found_rows + y0, found_cols + x0, small.side)


def grow_blob(rgb: np.ndarray, blob: HandleBlob, door: ColourStats, options: DetectionOptions) -> HandleBlob:
    """The blob plus the connected pixels around it that have the handle's colour.

    Seen at an angle, a handle standing 6 cm proud of the door projects past the door's
    edge, out of the search strip; this recovers it.  In a window around the blob (grown
    by its height and half its width), pixels that are not door-coloured and within
    ``HANDLE_GROW_SIGMAS``·σ of the blob's own (robust) colour are added when connected
    to it; blob pixels of another colour are dropped.  A growth that reaches the window's
    border (it leaked into a frame or wall of a similar colour) or multiplies the area by
    more than ``HANDLE_GROW_LIMIT`` is abandoned: the blob's own pixels of the handle's
    colour (their largest connected part) are returned.
    """
    height, width = rgb.shape[:2]
    margin_x = int(max(np.ptp(blob.rows) + 1, (np.ptp(blob.cols) + 1) // 2))
    margin_y = int(np.ptp(blob.rows) + 1)
    x0, x1 = max(int(blob.cols.min()) - margin_x, 0), min(int(blob.cols.max()) + margin_x + 1, width)
    y0, y1 = max(int(blob.rows.min()) - margin_y, 0), min(int(blob.rows.max()) + margin_y + 1, height)
    window = rgb[y0:y1, x0:x1]
    own = robust_colour_stats(rgb[blob.rows, blob.cols])
    mask = own.matches(window, options, HANDLE_GROW_SIGMAS) & ~door.matches(window, options)
    _, labels = cv2.connectedComponents(mask.astype(np.uint8), connectivity=8)
    seeds = labels[blob.rows - y0, blob.cols - x0]
    keep = np.unique(seeds[seeds > 0])
    if keep.size == 0:
        return blob
    grown = np.isin(labels, keep)
    leaked = grown[0].any() or grown[-1].any() or grown[:, 0].any() or grown[:, -1].any()
    if leaked or grown.sum() > HANDLE_GROW_LIMIT * blob.area:
        core = seeds == np.bincount(seeds[seeds > 0]).argmax()
        return HandleBlob(blob.rows[core], blob.cols[core], blob.side) if core.sum() >= 3 else blob
    rows, cols = np.nonzero(grown)
    return HandleBlob(rows + y0, cols + x0, blob.side)


def _side_blob(crop: _DoorCrop, not_door: np.ndarray, side: Side, door_area: float,
               options: DetectionOptions, scale: float = 1.0) -> HandleBlob | None:
    """Largest admissible non-door connected component of one side strip in the band.

    Admissible: area within the thresholds, not touching the band's top or bottom (a
    handle lies inside the band; frames, edges and shadows cross it) and not taller than
    ``handle_max_aspect`` times its width (handles are levers or knobs).
    """
    m, f = options.door_margin_fraction, options.handle_side_fraction
    t_low, t_high = (m, f) if side is Side.LEFT else (1 - f, 1 - m)
    band_low = options.handle_band_low if crop.bottom_visible else m
    band_high = options.handle_band_high if crop.top_visible else 1 - m
    region = (crop.t >= t_low) & (crop.t <= t_high) & (crop.h >= band_low) & (crop.h <= band_high)
    mask = (region & not_door).astype(np.uint8)
    count, labels, stats, _ = cv2.connectedComponentsWithStats(mask, connectivity=8)
    if count < 2:
        return None
    areas = stats[1:, cv2.CC_STAT_AREA]
    low = max(options.handle_min_area * scale ** 2, options.handle_min_area_fraction * door_area)
    high = options.handle_max_area_fraction * door_area
    compact = stats[1:, cv2.CC_STAT_HEIGHT] <= options.handle_max_aspect * stats[1:, cv2.CC_STAT_WIDTH]
    crossing = np.zeros(count, dtype=bool)
    crossing[np.unique(labels[_band_ends(crop, region, band_low, band_high)])] = True
    admissible = np.flatnonzero((areas >= low) & (areas <= high) & compact & ~crossing[1:])
    if admissible.size == 0:
        return None
    label = int(admissible[np.argmax(areas[admissible])]) + 1
    rows, cols = np.nonzero(labels == label)
    return HandleBlob(rows + crop.y0, cols + crop.x0, side)


def _band_ends(crop: _DoorCrop, region: np.ndarray, low: float, high: float) -> np.ndarray:
    """Pixels of ``region`` in the first or last 1.5 rows of the band [low, high] of h."""
    rows = max(crop.h.shape[0], 1)
    step = 1.5 * float(np.ptp(crop.h[:, 0])) / rows if rows > 1 else 0.0
    return region & ((crop.h <= low + step) | (crop.h >= high - step))
