"""Image ↔ ndarray converters: every encoding round-trips; bad images raise clear errors."""

import numpy as np
import pytest
from sensor_msgs.msg import Image

from door_contract.converters.image import array_to_image, depth_to_metres, image_to_array
from door_contract.errors import EncodingError, ShapeError

RNG = np.random.default_rng(7)
SAMPLES = {
    "rgb8": RNG.integers(0, 255, (4, 5, 3), dtype=np.uint8),
    "bgr8": RNG.integers(0, 255, (4, 5, 3), dtype=np.uint8),
    "mono8": RNG.integers(0, 255, (4, 5), dtype=np.uint8),
    "32FC1": RNG.uniform(0.3, 5.0, (4, 5)).astype(np.float32),
    "16UC1": RNG.integers(300, 5000, (4, 5), dtype=np.uint16),
}


@pytest.mark.parametrize("encoding", sorted(SAMPLES))
def test_round_trip(encoding):
    array = SAMPLES[encoding]
    msg = array_to_image(array, encoding, frame_id="cam", stamp=12.5)
    assert (msg.width, msg.height, msg.encoding) == (5, 4, encoding)
    assert msg.header.stamp.sec == 12 and msg.header.stamp.nanosec == 500_000_000
    back = image_to_array(msg)
    assert back.dtype == array.dtype
    np.testing.assert_array_equal(back, array)


def test_padded_rows_are_cropped():
    array = SAMPLES["mono8"]
    msg = Image(height=4, width=5, encoding="mono8", step=8)
    msg.data = np.pad(array, ((0, 0), (0, 3)), constant_values=99).tobytes()
    np.testing.assert_array_equal(image_to_array(msg), array)


def test_big_endian_float_depth():
    depth = SAMPLES["32FC1"]
    msg = Image(height=4, width=5, encoding="32FC1", step=20, is_bigendian=1)
    msg.data = depth.astype(">f4").tobytes()
    np.testing.assert_array_equal(image_to_array(msg), depth)


def test_depth_in_millimetres_becomes_metres_and_zero_becomes_nan():
    mm = SAMPLES["16UC1"].copy()
    mm[0, 0] = 0
    metres = depth_to_metres(array_to_image(mm, "16UC1"))
    assert np.isnan(metres[0, 0])
    np.testing.assert_allclose(metres[1:], mm[1:] / 1000.0, rtol=1e-6)


def test_unsupported_encoding_is_named():
    msg = Image(height=1, width=1, encoding="yuv422", step=2, data=b"\x00\x00")
    with pytest.raises(EncodingError, match="yuv422"):
        image_to_array(msg)


def test_colour_image_is_not_depth():
    with pytest.raises(EncodingError, match="32FC1"):
        depth_to_metres(array_to_image(SAMPLES["rgb8"], "rgb8"))


@pytest.mark.parametrize("height, width, step, size", [
    (4, 5, 15, 60 - 1),   # data one byte short
    (4, 5, 14, 56),       # step smaller than a row
    (0, 5, 15, 0),        # empty
])
def test_size_mismatch(height, width, step, size):
    msg = Image(height=height, width=width, encoding="rgb8", step=step, data=bytes(size))
    with pytest.raises(ShapeError):
        image_to_array(msg)


def test_array_must_match_encoding():
    with pytest.raises(ShapeError):
        array_to_image(SAMPLES["mono8"], "rgb8")
    with pytest.raises(EncodingError):
        array_to_image(SAMPLES["32FC1"].astype(np.float64), "32FC1")
