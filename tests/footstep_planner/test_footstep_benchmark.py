"""The benchmark runs and prints the paper's figure, ours and the ratio for every scenario."""

from __future__ import annotations

import pytest

from footstep_planner.benchmark import PAPER_FIGURE, main


def test_benchmark_prints_a_row_per_scenario_and_planner(capsys: pytest.CaptureFixture[str]
                                                         ) -> None:
    assert main(["--repeats", "1"]) == 0
    table = capsys.readouterr().out
    rows = [line for line in table.splitlines() if PAPER_FIGURE in line]
    assert len(rows) == 6  # 3 scenarios x (A*, weighted A*)
    assert all(row.rstrip().endswith("success") for row in rows)
    assert "weighted A* w=2" in table
