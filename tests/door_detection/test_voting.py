"""The vote over N frames (seed 001 Sec. III-A, last paragraph)."""

from __future__ import annotations

import numpy as np

from door_detection.estimate import DetectionMode, DetectionOutcome, DetectionResult, DoorEstimate, Side
from door_detection.options import DetectionOptions
from door_detection.voting import Voter


def _estimate(x: float, normal=(0.0, 0.0, -1.0), side: Side = Side.LEFT) -> DoorEstimate:
    corners = np.array([[-0.45, 1.0, 2.0], [0.45, 1.0, 2.0], [0.45, -1.0, 2.0], [-0.45, -1.0, 2.0]])
    return DoorEstimate(np.array([x, 0.1, 2.0]), np.array(normal), side, 0.9, corners, 0.95,
                        DetectionMode.AUTOMATIC)


def test_an_outlier_is_voted_out() -> None:
    voter = Voter(DetectionOptions(vote_frames=10))
    xs = [0.30, 0.31, 0.29, 0.80, 0.30, 0.305, 0.295]         # 0.80: a wrong handle
    results = [voter.add(_estimate(x)) for x in xs]
    assert [r.outcome for r in results[:5]] == [DetectionOutcome.VOTING] * 5
    final = results[-1]
    assert final.outcome is DetectionOutcome.DETECTED     # 6 of 10 agree: ⌊10/2⌋ + 1
    assert final.agreeing == 6
    assert abs(final.estimate.handle_position[0] - 0.30) < 0.005
    assert final.estimate.confidence == 0.6
    assert final.estimate.frames_voted == 6


def test_failed_frames_count_against_the_majority() -> None:
    voter = Voter(DetectionOptions(vote_frames=4))
    failure = DetectionResult(DetectionOutcome.NO_HANDLE, None, "no handle")
    outcomes = [voter.add(item).outcome for item in (_estimate(0.3), failure, None, _estimate(0.3))]
    assert outcomes == [DetectionOutcome.VOTING] * 3 + [DetectionOutcome.NO_CONSENSUS]
    assert voter.add(_estimate(0.3)).outcome is DetectionOutcome.NO_CONSENSUS  # 2 of 4
    assert voter.add(_estimate(0.3)).outcome is DetectionOutcome.DETECTED      # 3 of 4: slid


def test_normals_and_hinge_sides_must_agree_too() -> None:
    voter = Voter(DetectionOptions(vote_frames=3))
    tilted = (np.sin(np.radians(10)), 0.0, -np.cos(np.radians(10)))
    voter.add(_estimate(0.3))
    voter.add(_estimate(0.3, normal=tilted))
    result = voter.add(_estimate(0.3, side=Side.RIGHT))
    assert result.outcome is DetectionOutcome.NO_CONSENSUS


def test_consensus_normal_is_a_unit_vector_and_reset_forgets() -> None:
    voter = Voter(DetectionOptions(vote_frames=3))
    tilt = (np.sin(np.radians(2)), 0.0, -np.cos(np.radians(2)))
    voter.add(_estimate(0.3))
    result = voter.add(_estimate(0.31, normal=tilt))
    assert result.ok
    assert np.isclose(np.linalg.norm(result.estimate.normal), 1.0)
    voter.reset()
    assert len(voter) == 0 and voter.decide().outcome is DetectionOutcome.VOTING


def test_single_frame_vote() -> None:
    result = Voter(DetectionOptions(vote_frames=1)).add(_estimate(0.3))
    assert result.ok and result.estimate.confidence == 1.0
