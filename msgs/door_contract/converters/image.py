"""``sensor_msgs/Image`` ↔ ``numpy.ndarray``.

Supported encodings: rgb8, bgr8 (H×W×3 uint8), mono8 (H×W uint8), 32FC1 (H×W float32) and
16UC1 (H×W uint16, depth in millimetres). Rows may be padded (``step`` > width × pixel size).
Data are wrapped with ``np.frombuffer`` and written with ``ndarray.tobytes()`` (50 ms vs
0.06 ms per VGA frame when a message is built element by element).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
from sensor_msgs.msg import Image

from door_contract.errors import EncodingError, ShapeError
from door_contract.stamps import Stamp, to_time_msg

__all__ = ["PIXEL_FORMATS", "PixelFormat", "array_to_image", "depth_to_metres", "image_to_array"]


@dataclass(frozen=True)
class PixelFormat:
    dtype: np.dtype
    channels: int

    @property
    def pixel_bytes(self) -> int:
        return self.dtype.itemsize * self.channels


PIXEL_FORMATS = {
    "rgb8": PixelFormat(np.dtype(np.uint8), 3),
    "bgr8": PixelFormat(np.dtype(np.uint8), 3),
    "mono8": PixelFormat(np.dtype(np.uint8), 1),
    "32FC1": PixelFormat(np.dtype(np.float32), 1),
    "16UC1": PixelFormat(np.dtype(np.uint16), 1),
}


def _pixel_format(encoding: str) -> PixelFormat:
    try:
        return PIXEL_FORMATS[encoding]
    except KeyError:
        raise EncodingError(
            f"unsupported image encoding {encoding!r}; supported: {', '.join(PIXEL_FORMATS)}"
        ) from None


def image_to_array(msg: Image) -> np.ndarray:
    """The image as an H×W(×C) array in the encoding's dtype (a read-only view when possible)."""
    fmt = _pixel_format(msg.encoding)
    if msg.height == 0 or msg.width == 0:
        raise ShapeError(f"empty image ({msg.width}×{msg.height})")
    row_bytes = msg.width * fmt.pixel_bytes
    if msg.step < row_bytes:
        raise ShapeError(f"step {msg.step} < width × pixel size = {row_bytes} for {msg.encoding}")
    data = np.frombuffer(msg.data, dtype=np.uint8)
    if data.size != msg.step * msg.height:
        raise ShapeError(f"data has {data.size} bytes, step × height = {msg.step * msg.height}")
    rows = data.reshape(msg.height, msg.step)[:, :row_bytes]
    byte_order: Literal[">", "<"] = ">" if msg.is_bigendian else "<"
    pixels = np.ascontiguousarray(rows).view(fmt.dtype.newbyteorder(byte_order))
    shape = (msg.height, msg.width, fmt.channels) if fmt.channels > 1 else (msg.height, msg.width)
    return pixels.reshape(shape).astype(fmt.dtype, copy=False)


def array_to_image(array: np.ndarray, encoding: str, frame_id: str = "",
                   stamp: Stamp | None = None) -> Image:
    """An Image message holding ``array`` (dtype and channel count must match ``encoding``)."""
    fmt = _pixel_format(encoding)
    expected_ndim = 3 if fmt.channels > 1 else 2
    if array.ndim != expected_ndim or (fmt.channels > 1 and array.shape[2] != fmt.channels):
        raise ShapeError(f"{encoding} needs an array of shape H×W" +
                         (f"×{fmt.channels}" if fmt.channels > 1 else "") + f", got {array.shape}")
    if array.dtype != fmt.dtype:
        raise EncodingError(f"{encoding} needs dtype {fmt.dtype}, got {array.dtype}")
    if array.shape[0] == 0 or array.shape[1] == 0:
        raise ShapeError(f"empty image {array.shape}")
    msg = Image()
    msg.header.frame_id = frame_id
    if stamp is not None:
        msg.header.stamp = to_time_msg(stamp)
    msg.height, msg.width = int(array.shape[0]), int(array.shape[1])
    msg.encoding = encoding
    msg.is_bigendian = 0
    msg.step = msg.width * fmt.pixel_bytes
    msg.data = np.ascontiguousarray(array, dtype=fmt.dtype.newbyteorder("<")).tobytes()
    return msg


def depth_to_metres(msg: Image) -> np.ndarray:
    """Depth in metres as float32; invalid pixels (0 mm, NaN, ±inf, ≤ 0) become NaN.

    32FC1 is already in metres; 16UC1 is millimetres (REP-118).
    """
    if msg.encoding not in ("32FC1", "16UC1"):
        raise EncodingError(f"depth must be 32FC1 (m) or 16UC1 (mm), got {msg.encoding!r}")
    raw = image_to_array(msg)
    metres = raw.astype(np.float32) / 1000.0 if msg.encoding == "16UC1" else raw.astype(np.float32)
    return np.where(np.isfinite(metres) & (metres > 0.0), metres, np.float32(np.nan))
