"""Input checks and the image filtering of the automatic detector ([Banerjee 2015] Sec. III-A).

:func:`validate_frame` turns the raw inputs into a :class:`RgbdFrame` or raises
:class:`~door_detection.errors.InputError` (:class:`DepthError` when the depth holds no
valid pixel); :func:`edge_image` is the paper's filter chain, histogram equalisation →
bilateral filter → Canny, run on a down-scaled image for speed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import cv2
import numpy as np

from door_contract.converters.camera_info import CameraIntrinsics
from door_detection.errors import InputError
from door_detection.options import DetectionOptions

__all__ = ["DepthError", "RgbdFrame", "check_intrinsics", "edge_image", "equalise_luma", "validate_frame",
           "validate_rgb"]


class DepthError(InputError):
    """The depth image (or the region the detector needs) has no valid pixel."""


@dataclass(frozen=True)
class RgbdFrame:
    """A checked RGB-D frame: ``rgb`` H×W×3 uint8, ``depth`` H×W float32 metres with
    every invalid or out-of-range reading set to NaN, and matching ``intrinsics``."""

    rgb: np.ndarray
    depth: np.ndarray
    intrinsics: CameraIntrinsics

    @property
    def height(self) -> int:
        return int(self.rgb.shape[0])

    @property
    def width(self) -> int:
        return int(self.rgb.shape[1])


def validate_frame(rgb: np.ndarray, depth: np.ndarray, intrinsics: CameraIntrinsics,
                   options: DetectionOptions) -> RgbdFrame:
    """Check shapes, dtypes and intrinsics; mask depth outside [min_depth, max_depth]."""
    colour = validate_rgb(rgb)
    check_intrinsics(intrinsics, colour.shape[1], colour.shape[0])
    metres = _validate_depth(depth, colour.shape[:2], options)
    return RgbdFrame(colour, metres, intrinsics)


def validate_rgb(rgb: np.ndarray) -> np.ndarray:
    """An H×W×3 uint8 image (mono H×W is expanded to three channels)."""
    image = np.asarray(rgb)
    if image.ndim == 2:
        image = np.repeat(image[:, :, None], 3, axis=2)
    if image.ndim != 3 or image.shape[2] != 3:
        raise InputError(f"colour image must be H×W×3 (rgb8), got shape {image.shape}")
    if image.shape[0] == 0 or image.shape[1] == 0:
        raise InputError(f"colour image is empty ({image.shape[1]}×{image.shape[0]})")
    if image.dtype != np.uint8:
        raise InputError(f"colour image must be uint8, got {image.dtype}")
    return image


def check_intrinsics(intrinsics: CameraIntrinsics, width: int, height: int) -> None:
    """Raise :class:`InputError` when the intrinsics are not finite, not positive, or
    describe an image of another size."""
    values = (intrinsics.fx, intrinsics.fy, intrinsics.cx, intrinsics.cy)
    if not all(math.isfinite(float(v)) for v in values):
        raise InputError(f"intrinsics must be finite, got fx, fy, cx, cy = {values}")
    if intrinsics.fx <= 0 or intrinsics.fy <= 0:
        raise InputError(f"focal lengths must be > 0, got fx={intrinsics.fx}, fy={intrinsics.fy}")
    if (intrinsics.width, intrinsics.height) != (width, height):
        raise InputError(f"intrinsics are for a {intrinsics.width}×{intrinsics.height} image "
                         f"but the image is {width}×{height}")


def _validate_depth(depth: np.ndarray, shape: tuple[int, int], options: DetectionOptions) -> np.ndarray:
    array = np.asarray(depth)
    if array.ndim != 2 or array.shape != shape:
        raise InputError(f"depth must be registered to the colour image ({shape[1]}×{shape[0]}), "
                         f"got shape {array.shape}")
    if not np.issubdtype(array.dtype, np.floating):
        raise InputError(f"depth must be float metres (32FC1), got {array.dtype}")
    metres = array.astype(np.float32, copy=True)
    with np.errstate(invalid="ignore"):
        invalid = ~((metres >= options.min_depth) & (metres <= options.max_depth))
    metres[invalid] = np.nan
    if invalid.all():
        raise DepthError(f"depth has no valid pixel in [{options.min_depth}, {options.max_depth}] m")
    return metres


def equalise_luma(luma: np.ndarray, clip_limit: float) -> np.ndarray:
    """Histogram equalisation of an 8-bit image, contrast-limited when ``clip_limit`` > 0.

    Plain equalisation maps level L to 255·CDF(L): a scene of one dominant grey (a white
    leaf in a white wall and frame) sends that grey to 254 and every brighter level to 255,
    erasing the 11-level step of a lit jamb face. Clipping each histogram bin at
    ``clip_limit`` × the mean bin height and spreading the excess evenly (OpenCV's CLAHE on
    a single tile) bounds the mapping's slope by about ``clip_limit`` + 1, so a small step
    stays a step while a dim image is still stretched.
    """
    if clip_limit <= 0.0:
        return cv2.equalizeHist(luma)
    return cv2.createCLAHE(clipLimit=clip_limit, tileGridSize=(1, 1)).apply(luma)


def edge_image(rgb: np.ndarray, options: DetectionOptions) -> np.ndarray:
    """Canny edges of the scaled, equalised, bilateral-filtered image (Sec. III-A).

    The image is first shrunk by ``line_scale`` (INTER_AREA).  Histogram equalisation
    (the paper's first step; contrast-limited, :func:`equalise_luma`) is applied to the luma
    Y of YCrCb, spreading the grey levels over 0..255 so fixed Canny thresholds work under
    any exposure; the bilateral filter
    smooths texture but keeps edges; Canny runs on all three channels (OpenCV takes the
    strongest channel gradient).  Beyond the paper: keeping the chroma finds edges
    between surfaces of equal brightness (a light-wood door in a white-grey frame, whose
    grey levels equalisation brings within a few levels of each other).
    """
    small = rgb
    if options.line_scale < 1.0:
        small = cv2.resize(rgb, None, fx=options.line_scale, fy=options.line_scale,
                           interpolation=cv2.INTER_AREA)
    ycc = cv2.cvtColor(small, cv2.COLOR_RGB2YCrCb)
    ycc[:, :, 0] = equalise_luma(ycc[:, :, 0], options.histogram_clip_limit)
    smooth = cv2.bilateralFilter(ycc, options.bilateral_diameter,
                                 options.bilateral_sigma_color, options.bilateral_sigma_space)
    return cv2.Canny(smooth, options.canny_low, options.canny_high)


