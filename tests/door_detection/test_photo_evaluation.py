"""The photo evaluation and the progress bar run and return sane numbers (no timing asserts).
The evaluations on the simulator are tested in tests/door_evaluation."""

from __future__ import annotations

import math

import pytest

from door_detection import evaluate_photos
from door_detection.progress import ProgressBar


def test_photo_evaluation_on_three_labelled_photos(shared_data) -> None:
    images = [image for image in evaluate_photos.load_dataset(shared_data / "doors" / "detectdoor")
              if image.of_class(evaluate_photos.DOOR)][:3]
    assert len(images) == 3
    report = evaluate_photos.evaluate(images, progress=False)
    assert report.images == 3 and report.doors >= 3 and report.handles >= 3
    for value in (report.door_found, report.door_top1_precision, report.handle_found,
                  report.handle_centre_hit):
        assert 0.0 <= value <= 1.0
    assert math.isnan(report.door_false_detections)          # no image without doors among the 3
    assert "doors found" in report.text()


def test_photo_labels_are_parsed_in_pixels(shared_data) -> None:
    dataset = evaluate_photos.load_dataset(shared_data / "doors" / "detectdoor")
    images = {image.path.stem: image for image in dataset}
    door = images["000c9e454bbf6d0d"].of_class(evaluate_photos.DOOR)[0]   # 678×1024, cx 0.477
    assert door[0] == pytest.approx((0.477344 - 0.479688 / 2) * 678, abs=0.5)
    assert images["00eb261110ac46c5"].boxes == ()                         # a negative


def test_progress_bar_writes_to_its_stream() -> None:
    import io

    stream = io.StringIO()
    bar = ProgressBar(2, stream=stream)
    bar.advance("one")
    bar.advance("two")
    bar.close()
    assert "2/2" in stream.getvalue() and stream.getvalue().endswith("\n")
