"""The benchmark runs and prints, per family of searches, the paper's figure, ours and the
ratio to the 50 ms target, and every search of the sweep succeeds."""

from __future__ import annotations

import pytest

from door_evaluation.footsteps.benchmark import PAPER_FIGURE, main


def test_benchmark_prints_a_row_per_family_and_every_search_succeeds(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["--repeats", "1", "--grid", "coarse"]) == 0
    table = capsys.readouterr().out
    rows = [line.split() for line in table.splitlines() if PAPER_FIGURE in line]
    families = [line for line in table.splitlines() if PAPER_FIGURE in line]
    assert any(line.startswith("approach (push)") for line in families)
    assert any(line.startswith("approach (pull)") for line in families)
    assert any("pull passage: turn towards the hinge" in line for line in families)
    assert any("push passage: side-step through the doorway" in line for line in families)
    for row in rows:  # ... cases ok median ms max ms ratio expansions
        cases, successes = int(row[-12]), int(row[-11])
        assert successes == cases, row
