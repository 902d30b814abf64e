"""Errors raised by the message contract's converters and parameter validation.

:class:`ContractError` is the package's one base error. It is deliberately *not* a
:class:`ValueError`: a node that rejects a message on ``except ContractError`` must not also
reject the ``ValueError`` of a bug (numpy, float(), an enum lookup) as bad input.
"""

__all__ = ["ContractError", "EncodingError", "NonFiniteError", "ParameterRangeError", "ShapeError"]


class ContractError(Exception):
    """A message or parameter does not satisfy the contract; the message says which part."""


class EncodingError(ContractError):
    """An image encoding the converter does not support, or one that contradicts the data."""


class ShapeError(ContractError):
    """Sizes that do not agree: width × height × channels vs data length, step, array shape."""


class NonFiniteError(ContractError):
    """NaN or infinity where the contract requires finite numbers (poses, joint positions)."""


class ParameterRangeError(ContractError):
    """A node parameter outside its declared type or range; the message names both."""
