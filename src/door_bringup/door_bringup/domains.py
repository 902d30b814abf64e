"""ROS domain ids leased host-wide, so concurrent campaigns never share DDS.

A Monte-Carlo worker used to take ``ROS_DOMAIN_ID + 1 …`` from its own queue: two campaigns
started from the same shell (or a campaign and a main job) took the same ids, and their graphs
answered each other's requests (two main jobs on one domain failed WALK_TO_DOOR with
"superseded by request 2"). A lease is an exclusive ``flock`` on ``<directory>/<id>.lock``,
taken without blocking on the first free id from a starting one, and held by a raw file
descriptor until it is released or the process exits (the kernel drops the lock then, even
after a crash).
"""

from __future__ import annotations

import fcntl
import os
import tempfile
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

__all__ = ["DOMAIN_COUNT", "DomainLease", "DomainsExhausted", "default_lock_directory", "lease_domain",
           "lease_wanted_domain"]

DOMAIN_COUNT = 233
"""The domain ids DDS allows on one host (0-232)."""


class DomainsExhausted(RuntimeError):
    """Every domain id is leased by another process."""


@dataclass(frozen=True)
class DomainLease:
    """A domain id this process holds (``fd``: the locked lock file's descriptor)."""

    domain: int
    fd: int

    def release(self) -> None:
        """Give the id back (closing the descriptor drops the lock)."""
        os.close(self.fd)


def default_lock_directory() -> Path:
    """``<tmp>/door_task_domains``, created when missing."""
    directory = Path(tempfile.gettempdir()) / "door_task_domains"
    directory.mkdir(parents=True, exist_ok=True)
    return directory


def lease_domain(first: int, directory: Path | None = None, count: int = DOMAIN_COUNT) -> DomainLease:
    """The first of the ``count`` ids from ``first`` (modulo :data:`DOMAIN_COUNT`) no other
    lease holds (the test session's and every Monte-Carlo worker's share these locks)."""
    folder = default_lock_directory() if directory is None else directory
    for offset in range(min(count, DOMAIN_COUNT)):
        domain = (first + offset) % DOMAIN_COUNT
        fd = os.open(folder / f"{domain}.lock", os.O_CREAT | os.O_RDWR, 0o644)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            os.close(fd)
            continue
        return DomainLease(domain, fd)
    last = (first + min(count, DOMAIN_COUNT) - 1) % DOMAIN_COUNT
    raise DomainsExhausted(f"every ROS domain id in {first}..{last} is leased (lock files in {folder})")


def lease_wanted_domain(environ: Mapping[str, str], directory: Path | None = None) -> tuple[DomainLease, int]:
    """The lease of a main job: the domain ``environ`` asks for (``ROS_DOMAIN_ID``, default 0)
    if no other run holds it, else the next free one; with the id that was asked for. Two main
    jobs started side by side shared domain 0 and answered each other's approvals.
    ValueError when ``ROS_DOMAIN_ID`` is not an id of 0-232."""
    text = environ.get("ROS_DOMAIN_ID", "").strip() or "0"
    if not text.isdigit() or int(text) >= DOMAIN_COUNT:
        raise ValueError(f"ROS_DOMAIN_ID = {text!r} is not a ROS domain id (an integer in [0, {DOMAIN_COUNT - 1}])")
    wanted = int(text)
    return lease_domain(wanted, directory), wanted
