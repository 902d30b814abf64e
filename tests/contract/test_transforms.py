"""4×4 ↔ TransformStamped ↔ TFMessage: round trips, stamps, and NaN refused."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from door_contract.converters.transforms import (
    TfMessageBuffer,
    frame_transform_to_msg,
    matrix_to_transform,
    msg_to_frame_transform,
    tf_message,
    tf_message_frames,
    tf_messages_available,
    transform_to_matrix,
)
from door_contract.errors import NonFiniteError, ShapeError
from door_contract.frames import FrameTransform


def _matrix(seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    matrix = np.eye(4)
    matrix[:3, :3] = Rotation.random(random_state=seed).as_matrix()
    matrix[:3, 3] = rng.uniform(-2, 2, 3)
    return matrix


def test_transform_round_trip():
    for seed in range(5):
        np.testing.assert_allclose(transform_to_matrix(matrix_to_transform(_matrix(seed))), _matrix(seed), atol=1e-12)


def test_stamped_carries_frames_and_stamp():
    msg = frame_transform_to_msg(FrameTransform("odom", "base_link", _matrix(1)), 12.25)
    assert (msg.header.frame_id, msg.child_frame_id) == ("odom", "base_link")
    assert (msg.header.stamp.sec, msg.header.stamp.nanosec) == (12, 250_000_000)
    back = msg_to_frame_transform(msg)
    assert (back.parent, back.child) == ("odom", "base_link")
    np.testing.assert_allclose(back.matrix, _matrix(1), atol=1e-12)


def test_non_finite_transforms_are_refused():
    bad = _matrix(2)
    bad[0, 3] = np.nan
    with pytest.raises(NonFiniteError):
        matrix_to_transform(bad)


def test_tf_message_holds_every_frame():
    assert tf_messages_available(), "tf2_msgs is missing: ./setup.sh builds it (interfaces/)"
    frames = [FrameTransform("odom", "base_link", _matrix(3)), FrameTransform("base_link", "head", _matrix(4))]
    msg = tf_message(frames, 1.5)
    assert [t.child_frame_id for t in msg.transforms] == ["base_link", "head"]
    assert {t.header.stamp.sec for t in msg.transforms} == {1}
    np.testing.assert_allclose(tf_message_frames(msg)[1].matrix, _matrix(4), atol=1e-12)


def test_tf_message_refuses_non_finite_or_misshapen_transforms():
    bad = _matrix(5)
    bad[1, 1] = np.inf
    with pytest.raises(NonFiniteError):
        tf_message([FrameTransform("odom", "base_link", bad)], 0.0)
    with pytest.raises(ShapeError):
        tf_message([FrameTransform("odom", "base_link", np.eye(3))], 0.0)
    assert tf_message([], 0.0).transforms == []


def test_buffer_rewrites_numbers_in_place_and_rebuilds_when_frames_change():
    buffer = TfMessageBuffer()
    first = buffer.message([FrameTransform("odom", "base_link", _matrix(6))], 1.0)
    again = buffer.message([FrameTransform("odom", "base_link", _matrix(7))], 2.0)
    assert again is first and again.transforms[0].header.stamp.sec == 2
    np.testing.assert_allclose(tf_message_frames(again)[0].matrix, _matrix(7), atol=1e-12)
    other = buffer.message([FrameTransform("odom", "head", _matrix(7))], 3.0)
    assert other is not first and other.transforms[0].child_frame_id == "head"
