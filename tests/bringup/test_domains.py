"""Host-wide ROS domain leases (door_bringup.domains): no two holders share an id."""

import subprocess
import sys

import pytest

from door_bringup.domains import DOMAIN_COUNT, DomainsExhausted, lease_domain, lease_wanted_domain


def test_a_held_id_is_skipped_and_a_released_one_is_taken_again(tmp_path) -> None:
    first = lease_domain(40, tmp_path)
    second = lease_domain(40, tmp_path)
    assert (first.domain, second.domain) == (40, 41)
    first.release()
    again = lease_domain(40, tmp_path)
    assert again.domain == 40
    again.release()
    second.release()


def test_another_process_holding_an_id_keeps_it_until_it_exits(tmp_path) -> None:
    holder = subprocess.Popen([sys.executable, "-c",
                               "import sys, time; from pathlib import Path; from door_bringup.domains import lease_domain;"
                               f"lease = lease_domain(7, Path({str(tmp_path)!r})); print(lease.domain, flush=True);"
                               "sys.stdin.readline()"],
                              stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    try:
        assert holder.stdout is not None and holder.stdout.readline().strip() == "7"
        mine = lease_domain(7, tmp_path)
        assert mine.domain == 8
        mine.release()
    finally:
        holder.communicate("\n", timeout=30)
    after = lease_domain(7, tmp_path)  # the holder exited: the kernel dropped its lock
    assert after.domain == 7
    after.release()


def test_ids_wrap_around_and_run_out_with_a_clear_error(tmp_path) -> None:
    leases = [lease_domain(DOMAIN_COUNT - 1, tmp_path) for _ in range(DOMAIN_COUNT)]
    assert leases[0].domain == DOMAIN_COUNT - 1 and leases[1].domain == 0
    assert sorted(lease.domain for lease in leases) == list(range(DOMAIN_COUNT))
    with pytest.raises(DomainsExhausted, match="every ROS domain id in 0..232 is leased"):
        lease_domain(0, tmp_path)
    for lease in leases:
        lease.release()


def test_a_lease_can_be_bounded_to_a_range_of_ids(tmp_path) -> None:
    held = [lease_domain(10, tmp_path, count=2) for _ in range(2)]
    assert [lease.domain for lease in held] == [10, 11]
    with pytest.raises(DomainsExhausted, match="every ROS domain id in 10..11 is leased"):
        lease_domain(10, tmp_path, count=2)
    for lease in held:
        lease.release()


def test_a_main_job_takes_the_domain_it_asks_for_or_the_next_free_one(tmp_path) -> None:
    """Two main jobs side by side shared domain 0 and answered each other's approvals: the
    second now takes the next free id, and says which it asked for."""
    first, wanted = lease_wanted_domain({}, tmp_path)
    assert (first.domain, wanted) == (0, 0)
    second, wanted = lease_wanted_domain({"ROS_DOMAIN_ID": "0"}, tmp_path)
    assert (second.domain, wanted) == (1, 0)
    chosen, wanted = lease_wanted_domain({"ROS_DOMAIN_ID": " 42 "}, tmp_path)
    assert (chosen.domain, wanted) == (42, 42)
    for lease in (first, second, chosen):
        lease.release()


@pytest.mark.parametrize("text", ["-1", "233", "one", "4.5"])
def test_a_domain_id_that_is_not_one_is_refused_naming_it(text, tmp_path) -> None:
    with pytest.raises(ValueError, match=f"ROS_DOMAIN_ID = '{text}' is not a ROS domain id"):
        lease_wanted_domain({"ROS_DOMAIN_ID": text}, tmp_path)
