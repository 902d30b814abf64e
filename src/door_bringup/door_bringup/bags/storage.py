"""Read and write rosbag2 bags (sqlite3 and mcap) at the storage level, ROS-free.

Reading goes to the storage file itself — the sqlite ``topics``/``messages`` tables or the
MCAP channels — instead of matching the metadata's connections against the storage's:
``rosbags``' AnyReader and Reader yield **zero messages, silently**, for real
``ros2/rosbag2`` bags whose metadata QoS and topic ids differ from the storage file's
(ENVIRONMENT.md). Writing uses ``rosbags``' Writer (metadata version 9, as Jazzy writes), with
each topic's offered QoS profiles (what ``ros2 bag play`` restores: a transient-local topic
is replayed transient local), ``ros_distro: jazzy``, and optional zstd chunk compression for
mcap (what rosbag2's mcap plugin does with a zstd storage preset; readers decompress it).
"""

from __future__ import annotations

import heapq
import sqlite3
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from enum import Enum
from pathlib import Path

import yaml
from rosbags.interfaces import Connection, Qos
from rosbags.rosbag2 import ReaderError, StoragePlugin, Writer, WriterError
from rosbags.rosbag2.enums import CompressionFormat, CompressionMode
from rosbags.rosbag2.metadata import parse_qos
from rosbags.rosbag2.storage_mcap import McapReader
from rosbags.typesys import Stores, get_typestore

__all__ = ["BagError", "BagMessage", "BagMetadataError", "BagNotFoundError", "BagStorageError", "BagTopic",
           "BagWriteError", "BagWriter", "Compression", "StorageFormat", "list_topics", "read_messages", "recorded_qos"]

ROS_DISTRO = "jazzy"


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


class Compression(str, Enum):
    NONE = "none"
    ZSTD = "zstd"  # mcap chunks; Foxglove and rosbag2 read them as they are


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


def _bag_information(bag: Path) -> dict:
    metadata = bag / "metadata.yaml"
    if not metadata.is_file():
        raise BagNotFoundError(f"{bag} is neither a bag folder with metadata.yaml nor a .db3/.mcap file")
    try:
        return dict(yaml.safe_load(metadata.read_text())["rosbag2_bagfile_information"])
    except yaml.YAMLError as error:
        raise BagMetadataError(f"{metadata} is not YAML ({str(error).splitlines()[0]})") from None
    except (KeyError, TypeError, ValueError) as error:
        raise BagMetadataError(f"{metadata} lacks rosbag2_bagfile_information "
                               f"({type(error).__name__}: {error})") from None


def _storage_files(bag: Path) -> list[Path]:
    if bag.is_file():
        return [bag]
    info = _bag_information(bag)
    try:
        files = [bag / str(name) for name in info["relative_file_paths"]]
    except (KeyError, TypeError) as error:
        raise BagMetadataError(f"{bag / 'metadata.yaml'} lacks rosbag2_bagfile_information.relative_file_paths "
                               f"({type(error).__name__}: {error})") from None
    for path in files:
        if not path.is_file():
            raise BagMetadataError(f"{bag}: storage file {path.name} listed in metadata.yaml is missing")
    return files


def recorded_qos(bag: Path | str) -> dict[str, list[Qos]]:
    """Each topic's offered QoS profiles from ``metadata.yaml`` (both the YAML-string form of
    metadata ≤ 8 and the list of version 9); topics recorded without any map to []."""
    topics = _bag_information(Path(bag)).get("topics_with_message_count") or []
    try:
        return {entry["topic_metadata"]["name"]: parse_qos(entry["topic_metadata"].get("offered_qos_profiles") or [])
                for entry in topics}
    except (KeyError, TypeError, ValueError, AttributeError, ReaderError) as error:
        raise BagMetadataError(f"{bag}/metadata.yaml: unreadable topics_with_message_count "
                               f"({type(error).__name__}: {(str(error).splitlines() or [''])[0]})") from None


def _sqlite_messages(path: Path, topics: set[str] | None) -> Iterator[BagMessage]:
    # immutable=1: a read-only file system and no -shm/-wal side files next to the bag
    connection = sqlite3.connect(f"file:{path}?immutable=1", uri=True)
    where = ""
    names: tuple[str, ...] = ()
    if topics is not None:  # filtered in SQL: a run's bag holds ~400 MB of images
        names = tuple(sorted(topics))
        where = f"WHERE topics.name IN ({', '.join('?' * len(names))}) "
    try:
        rows = connection.execute(
            "SELECT topics.name, topics.type, messages.timestamp, messages.data FROM messages "
            f"JOIN topics ON messages.topic_id = topics.id {where}ORDER BY messages.timestamp, messages.id", names)
        for name, type_name, timestamp, data in rows:
            yield BagMessage(name, type_name, int(timestamp), bytes(data))
    except sqlite3.Error as error:
        raise BagStorageError(f"{path.name} is not a readable rosbag2 sqlite3 file ({error})") from None
    finally:
        connection.close()


def _mcap_messages(path: Path, topics: set[str] | None) -> Iterator[BagMessage]:
    reader, opened = McapReader(path), False
    try:
        reader.open()
        opened = True
        connections = [c for c in reader.connections if topics is None or c.topic in topics]
        for connection, timestamp, data in reader.messages(connections) if connections else ():
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
            streams.append(_sqlite_messages(path, wanted))
        elif path.suffix == ".mcap":
            streams.append(_mcap_messages(path, wanted))
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
    """Writes serialized messages to a new rosbag2 bag (metadata version 9, ``ros_distro: jazzy``)."""

    def __init__(self, path: Path | str, storage: StorageFormat = StorageFormat.SQLITE3,
                 compression: Compression = Compression.NONE) -> None:
        plugin = StoragePlugin.SQLITE3 if storage is StorageFormat.SQLITE3 else StoragePlugin.MCAP
        self.path = Path(path)
        if self.path.exists():
            raise BagWriteError(f"{path} exists already: choose a new output folder")
        if compression is Compression.ZSTD and storage is not StorageFormat.MCAP:
            raise BagWriteError("zstd compression is for mcap bags (compressed chunks); use --storage mcap")
        self._writer = Writer(self.path, version=9, storage_plugin=plugin)
        if compression is Compression.ZSTD:
            self._writer.set_compression(CompressionMode.STORAGE, CompressionFormat.ZSTD)
        self._typestore = get_typestore(Stores.ROS2_JAZZY)
        self._connections: dict[str, Connection] = {}
        try:
            self._writer.open()
        except (OSError, WriterError) as error:
            raise BagWriteError(f"cannot create {path} ({error})") from None
        self._say_jazzy_in_storage_metadata()

    def _say_jazzy_in_storage_metadata(self) -> None:
        """rosbags writes ``ros_distro: rosbags``; the copy of metadata.yaml that the storage
        file keeps (sqlite table, mcap record) gets Jazzy's, as rosbag2 itself writes."""
        storage = self._writer.storage
        if storage is None:  # open() makes it
            raise BagWriteError(f"{self.path}: the bag's storage is not open")
        close = storage.close
        # an instance attribute over the plugin's method: rosbags has no hook for the metadata it stores
        storage.close = lambda version, metadata: close(version, _jazzy(metadata))  # type: ignore[method-assign]

    def add_topic(self, topic: str, type_name: str, offered_qos: Iterable[Qos] = ()) -> None:
        """Declare ``topic`` with the QoS profiles its publishers offer (before its first message)."""
        if topic in self._connections:
            raise BagWriteError(f"topic {topic} is already in the bag")
        kwargs = {"typestore": self._typestore} if type_name in self._typestore.fielddefs else {
            "msgdef": "", "rihs01": ""}
        self._connections[topic] = self._writer.add_connection(
            topic, type_name, offered_qos_profiles=tuple(offered_qos), **kwargs)

    def write(self, topic: str, type_name: str, timestamp_ns: int, data: bytes) -> None:
        """Append a message; a topic not declared yet is added without QoS profiles."""
        if topic not in self._connections:
            self.add_topic(topic, type_name)
        self._writer.write(self._connections[topic], int(timestamp_ns), data)

    def close(self) -> None:
        self._writer.close()
        metadata = self.path / "metadata.yaml"
        metadata.write_text(_jazzy(metadata.read_text()))

    def __enter__(self) -> BagWriter:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def _jazzy(metadata_text: str) -> str:
    return metadata_text.replace("ros_distro: rosbags", f"ros_distro: {ROS_DISTRO}")
