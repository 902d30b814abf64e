"""The message contract of the door-traversal graph: topics, QoS, frames, units, converters.

Read :mod:`door_contract.topics` for the topic table; converters live in
:mod:`door_contract.converters`; JSON payloads in :mod:`door_contract.payloads`.
"""
