"""Bounded JSON parsing for the payloads on the bus: sizes and nesting are limited *before*
``json.loads`` runs, so no input can exhaust the parser.

``json.loads`` recurses once per ``[`` or ``{``: ``"[" * 100000`` raised RecursionError out of
the planners' decoding (issue #12). :func:`parse_bounded` counts the nesting depth in one
pass over the text (ignoring brackets inside strings) and refuses text longer than
``max_chars`` or nested deeper than ``max_depth`` with a :class:`ContractError`.
"""

from __future__ import annotations

import json
import re
from typing import Any

import numpy as np

from door_contract.errors import ContractError

__all__ = ["MAX_PAYLOAD_CHARS", "MAX_PAYLOAD_DEPTH", "nesting_depth", "parse_bounded", "read_request_id"]

MAX_PAYLOAD_CHARS = 4_000_000
"""Largest payload accepted (characters). A planning outcome carrying a 200-waypoint
trajectory twice is ~100 kB; camera data never travels as JSON."""

MAX_PAYLOAD_DEPTH = 16
"""Deepest nesting of arrays/objects accepted; the contract's payloads need at most 4."""

_JSON_STRING = re.compile(r'"(?:[^"\\]|\\.)*"?')
_OPENING = np.frombuffer(b"[{", dtype=np.uint8)
_CLOSING = np.frombuffer(b"]}", dtype=np.uint8)


def nesting_depth(text: str) -> int:
    """The deepest nesting of ``[``/``{`` in ``text``, brackets inside JSON strings ignored.

    Strings are cut out first (a JSON string is ``"`` … ``"`` with ``\\`` escapes); then
    depth is the running sum of +1 per opening and −1 per closing bracket, and the answer
    its maximum — vectorised, so a 4 MB text takes milliseconds.
    """
    skeleton = _JSON_STRING.sub("", text).encode("utf-8", "replace")
    codes = np.frombuffer(skeleton, dtype=np.uint8)
    steps = (np.isin(codes, _OPENING).astype(np.int64) - np.isin(codes, _CLOSING).astype(np.int64))
    return int(np.cumsum(steps).max(initial=0))


def parse_bounded(owner: str, text: str, max_chars: int = MAX_PAYLOAD_CHARS,
                  max_depth: int = MAX_PAYLOAD_DEPTH) -> Any:
    """``json.loads(text)`` after checking its size and nesting; ContractError names ``owner``."""
    if not isinstance(text, str):
        raise ContractError(f"{owner}: expected JSON text, got {type(text).__name__}")
    if len(text) > max_chars:
        raise ContractError(f"{owner}: {len(text)} characters, more than the {max_chars} allowed")
    depth = nesting_depth(text)
    if depth > max_depth:
        raise ContractError(f"{owner}: nested {depth} deep, more than the {max_depth} allowed")
    try:
        return json.loads(text)
    except (json.JSONDecodeError, RecursionError) as error:
        raise ContractError(f"{owner}: not JSON ({error})") from None


def read_request_id(text: str) -> int | None:
    """The ``request_id`` of a JSON request when it can be read, even if the rest is invalid.

    The contract promises one outcome per request id: a request with a readable id but
    missing, extra or wrong fields is answered REJECTED under that id (issue #12).
    """
    try:
        document = parse_bounded("request", text)
    except ContractError:
        return None
    if not isinstance(document, dict):
        return None
    request_id = document.get("request_id")
    if isinstance(request_id, int) and not isinstance(request_id, bool):
        return request_id
    return None
