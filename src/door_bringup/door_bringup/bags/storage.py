"""Read and write rosbag2 bags (sqlite3 and mcap) at the storage level, ROS-free.

Reading goes to the storage file itself — the sqlite ``topics``/``messages`` tables or the
MCAP channels — instead of matching the metadata's connections against the storage's:
``rosbags``' AnyReader and Reader yield **zero messages, silently**, for real
``ros2/rosbag2`` bags whose metadata QoS and topic ids differ from the storage file's
(ENVIRONMENT.md). Writing uses ``rosbags``' Writer (metadata version 9, as Jazzy writes).
"""

from __future__ import annotations

import heapq
import sqlite3
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from enum import Enum
from pathlib import Path

import yaml
from rosbags.rosbag2 import StoragePlugin, Writer, WriterError
from rosbags.rosbag2.storage_mcap import McapReader
from rosbags.typesys import Stores, get_typestore


class BagError(RuntimeError):
    """A bag that cannot be read or written: missing files, unknown storage."""


class BagNotFoundError(BagError):
    """Nothing at the path is a bag (no metadata.yaml, no .db3/.mcap file)."""


class BagMetadataError(BagError):
    """metadata.yaml is not YAML, lacks keys, or names files that are missing or unknown."""


class BagStorageError(BagError):
    """A storage file is truncated or corrupt (sqlite: malformed image; mcap: bad records)."""


class BagWriteError(BagError):
    """A bag cannot be created: the output exists, or its folder cannot be written."""


class StorageFormat(str, Enum):
    SQLITE3 = "sqlite3"
    MCAP = "mcap"


@dataclass(frozen=True)
class BagMessage:
    topic: str
    type_name: str
    timestamp_ns: int
    data: bytes  # CDR, as rclpy.serialization.serialize_message produces


@dataclass(frozen=True)
class BagTopic:
    name: str
    type_name: str
    message_count: int


def _storage_files(bag: Path) -> list[Path]:
    metadata = bag / "metadata.yaml"
    if bag.is_file():
        return [bag]
    if not metadata.is_file():
        raise BagNotFoundError(f"{bag} is neither a bag folder with metadata.yaml nor a .db3/.mcap file")
    try:
        info = yaml.safe_load(metadata.read_text())["rosbag2_bagfile_information"]
        files = [bag / str(name) for name in info["relative_file_paths"]]
    except yaml.YAMLError as error:
        raise BagMetadataError(f"{metadata} is not YAML ({str(error).splitlines()[0]})") from None
    except (KeyError, TypeError) as error:
        raise BagMetadataError(f"{metadata} lacks rosbag2_bagfile_information.relative_file_paths "
                               f"({type(error).__name__}: {error})") from None
    for path in files:
        if not path.is_file():
            raise BagMetadataError(f"{bag}: storage file {path.name} listed in metadata.yaml is missing")
    return files


def _sqlite_messages(path: Path) -> Iterator[BagMessage]:
    # immutable=1: a read-only file system and no -shm/-wal side files next to the bag
    connection = sqlite3.connect(f"file:{path}?immutable=1", uri=True)
    try:
        rows = connection.execute(
            "SELECT topics.name, topics.type, messages.timestamp, messages.data FROM messages "
            "JOIN topics ON messages.topic_id = topics.id ORDER BY messages.timestamp, messages.id")
        for name, type_name, timestamp, data in rows:
            yield BagMessage(name, type_name, int(timestamp), bytes(data))
    except sqlite3.Error as error:
        raise BagStorageError(f"{path.name} is not a readable rosbag2 sqlite3 file ({error})") from None
    finally:
        connection.close()


def _mcap_messages(path: Path) -> Iterator[BagMessage]:
    reader, opened = McapReader(path), False
    try:
        reader.open()
        opened = True
        for connection, timestamp, data in reader.messages(reader.connections):
            yield BagMessage(connection.topic, connection.msgtype, int(timestamp), bytes(data))
    except Exception as error:  # rosbags raises ReaderError, struct and Unicode errors on bad records
        raise BagStorageError(f"{path.name} is not a readable mcap file ({type(error).__name__}: {error})") from None
    finally:
        if opened:
            reader.close()


def read_messages(bag: Path | str, topics: Iterable[str] | None = None) -> Iterator[BagMessage]:
    """Every message of ``bag`` in time order (optionally only ``topics``)."""
    wanted = None if topics is None else set(topics)
    streams = []
    for path in _storage_files(Path(bag)):
        if path.suffix == ".db3":
            streams.append(_sqlite_messages(path))
        elif path.suffix == ".mcap":
            streams.append(_mcap_messages(path))
        else:
            raise BagMetadataError(f"unknown storage file {path.name} (expected .db3 or .mcap)")
    for message in heapq.merge(*streams, key=lambda m: m.timestamp_ns):
        if wanted is None or message.topic in wanted:
            yield message


def list_topics(bag: Path | str) -> list[BagTopic]:
    counts: dict[tuple[str, str], int] = {}
    for message in read_messages(bag):
        key = (message.topic, message.type_name)
        counts[key] = counts.get(key, 0) + 1
    return [BagTopic(name, type_name, count) for (name, type_name), count in sorted(counts.items())]


class BagWriter:
    """Writes serialized messages to a new rosbag2 bag (metadata version 9)."""

    def __init__(self, path: Path | str, storage: StorageFormat = StorageFormat.SQLITE3) -> None:
        plugin = StoragePlugin.SQLITE3 if storage is StorageFormat.SQLITE3 else StoragePlugin.MCAP
        if Path(path).exists():
            raise BagWriteError(f"{path} exists already: choose a new output folder")
        self._writer = Writer(Path(path), version=9, storage_plugin=plugin)
        self._typestore = get_typestore(Stores.ROS2_JAZZY)
        self._connections: dict[str, object] = {}
        try:
            self._writer.open()
        except (OSError, WriterError) as error:
            raise BagWriteError(f"cannot create {path} ({error})") from None

    def write(self, topic: str, type_name: str, timestamp_ns: int, data: bytes) -> None:
        connection = self._connections.get(topic)
        if connection is None:
            connection = self._add_connection(topic, type_name)
        self._writer.write(connection, int(timestamp_ns), data)

    def _add_connection(self, topic: str, type_name: str):
        if type_name in self._typestore.fielddefs:
            connection = self._writer.add_connection(topic, type_name, typestore=self._typestore)
        else:
            connection = self._writer.add_connection(topic, type_name, msgdef="", rihs01="")
        self._connections[topic] = connection
        return connection

    def close(self) -> None:
        self._writer.close()

    def __enter__(self) -> BagWriter:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
