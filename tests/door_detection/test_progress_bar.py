"""The evaluations' progress bar (door_detection.progress) draws on its stream; the evaluations
themselves are tested in tests/door_evaluation."""

from __future__ import annotations

from door_detection.progress import ProgressBar


def test_progress_bar_writes_to_its_stream() -> None:
    import io

    stream = io.StringIO()
    bar = ProgressBar(2, stream=stream)
    bar.advance("one")
    bar.advance("two")
    bar.close()
    assert "2/2" in stream.getvalue() and stream.getvalue().endswith("\n")
