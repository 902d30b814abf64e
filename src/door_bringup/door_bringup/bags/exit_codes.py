"""Exit codes of ``bag_play`` and ``bag_record``: one clear line and one code per failure class.

| code | meaning |
|---|---|
| 0 | done |
| 2 | bad arguments (``--rate 0``, an unknown option or storage, zstd without mcap) |
| 3 | no bag at the path |
| 4 | metadata.yaml unreadable: not YAML, missing keys, a listed storage file missing |
| 5 | a storage file is truncated or corrupt (.db3 or .mcap) |
| 6 | played, but some messages did not deserialize: reported, skipped and counted |
| 7 | bag_record: the output exists already or cannot be created |
"""

from __future__ import annotations

from enum import IntEnum

from door_bringup.bags.storage import BagError, BagMetadataError, BagNotFoundError, BagStorageError, BagWriteError

__all__ = ["BagExit", "exit_code_for"]


class BagExit(IntEnum):
    OK = 0
    USAGE = 2
    NOT_FOUND = 3
    BAD_METADATA = 4
    CORRUPT_STORAGE = 5
    SKIPPED_MESSAGES = 6
    CANNOT_WRITE = 7


def exit_code_for(error: BagError) -> BagExit:
    """The documented exit code of a bag error."""
    for kind, code in ((BagNotFoundError, BagExit.NOT_FOUND), (BagMetadataError, BagExit.BAD_METADATA),
                       (BagStorageError, BagExit.CORRUPT_STORAGE), (BagWriteError, BagExit.CANNOT_WRITE)):
        if isinstance(error, kind):
            return code
    return BagExit.CORRUPT_STORAGE
