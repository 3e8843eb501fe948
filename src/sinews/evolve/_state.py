"""Exact JSON encodings of arrays and random generators, for strategy checkpoints."""

from __future__ import annotations

import base64
import binascii
from typing import Any

import numpy as np
import numpy.typing as npt

from sinews.evolve.errors import StrategyError

__all__ = ["decode_array", "decode_rng", "encode_array", "encode_rng"]

_DTYPES = {"<f8": np.float64, "<i8": np.int64}
_BIT_GENERATORS = ("PCG64", "PCG64DXSM", "MT19937", "Philox", "SFC64")


def encode_array(array: npt.NDArray[Any]) -> dict[str, Any]:
    """A JSON-safe, bit-exact record of a float or integer array (as float64 or int64)."""
    dtype = "<f8" if np.issubdtype(array.dtype, np.floating) else "<i8"
    data = np.ascontiguousarray(array, dtype=dtype)
    return {
        "dtype": dtype,
        "shape": list(data.shape),
        "data": base64.b64encode(data.tobytes()).decode("ascii"),
    }


def decode_array(record: object, where: str) -> npt.NDArray[Any]:
    """The array of an `encode_array` record; `StrategyError` naming ``where`` if malformed."""
    if not isinstance(record, dict) or record.get("dtype") not in _DTYPES:
        raise StrategyError(f"checkpoint field {where!r} is not a valid array")
    try:
        shape = tuple(int(n) for n in record["shape"])
        raw = base64.b64decode(record["data"], validate=True)
        array = np.frombuffer(raw, dtype=record["dtype"]).reshape(shape)
    except (KeyError, TypeError, ValueError, binascii.Error):
        raise StrategyError(f"checkpoint field {where!r} is not a valid array") from None
    return array.astype(_DTYPES[record["dtype"]])


def encode_rng(rng: np.random.Generator) -> dict[str, Any]:
    """The generator's ``bit_generator.state`` (a JSON-safe dict of ints and names)."""
    return dict(rng.bit_generator.state)


def decode_rng(state: object) -> np.random.Generator:
    """A generator in exactly the state recorded by `encode_rng`."""
    name = state.get("bit_generator") if isinstance(state, dict) else None
    if name not in _BIT_GENERATORS:
        raise StrategyError("checkpoint field 'rng' is not a valid generator state")
    bit_generator = getattr(np.random, str(name))()
    try:
        bit_generator.state = state
    except (KeyError, TypeError, ValueError):
        raise StrategyError("checkpoint field 'rng' is not a valid generator state") from None
    return np.random.Generator(bit_generator)
