"""Genome codecs: how a genome becomes the bytes of an ``individuals.genome`` blob.

The store knows nothing of dancers: a run names its codec, and every genome
of the run is stored with it. ``float64`` and ``float32`` hold a flat float
vector as little-endian bytes (dancers, spring nets); ``json`` holds any
JSON value; ``gp-sexpr/1`` holds a GP program as its S-expression text,
UTF-8 (`sinews.control.gp.GENOME_CODEC`: the text names its terminals, so it
is read back with the run's primitive set). Decoding gives back exactly
what was encoded.
"""

from __future__ import annotations

import json
from typing import Any

import numpy as np

from sinews.store.errors import StoreError

__all__ = ["CODECS", "TEXT_CODECS", "decode_genome", "encode_genome"]

TEXT_CODECS = ("gp-sexpr/1",)
"""Codecs whose genomes are text."""
CODECS = ("float64", "float32", "json", *TEXT_CODECS)
_FLOAT_DTYPES: dict[str, np.dtype[Any]] = {"float64": np.dtype("<f8"), "float32": np.dtype("<f4")}


def encode_genome(genome: Any, codec: str) -> bytes:
    """The blob of ``genome`` under ``codec``.

    Args:
        genome: (G,) floats for the float codecs; any JSON value for ``json``;
            a string for the text codecs.
        codec: one of `CODECS`.

    Raises:
        StoreError: unknown codec, a genome that is not a flat vector (or
            not a string), or (``float32``) values that float32 cannot hold exactly.
    """
    if codec == "json":
        return json.dumps(genome, separators=(",", ":"), allow_nan=False).encode()
    if codec in TEXT_CODECS:
        if not isinstance(genome, str):
            raise StoreError(f"a {codec} genome must be text")
        return genome.encode("utf-8")
    dtype = _dtype(codec)
    values = np.asarray(genome)
    if values.ndim != 1 or not np.issubdtype(values.dtype, np.number):
        raise StoreError(f"a {codec} genome must be a flat vector of numbers")
    encoded = values.astype(dtype)
    if not np.array_equal(encoded, values):
        raise StoreError(f"this genome has values that {codec} cannot hold exactly")
    return encoded.tobytes()


def stored_json(text: str | bytes, what: str) -> Any:
    """A JSON document read back from the database (NaN and infinities allowed, as stored).

    Raises:
        StoreError: ``what`` is not JSON, or is nested too deep or has too long an integer.
    """
    try:
        return json.loads(text)
    except (ValueError, RecursionError):  # JSONDecodeError, bad UTF-8, huge integers
        raise StoreError(f"malformed {what} in the database (not readable JSON)") from None


def decode_genome(blob: bytes, codec: str) -> Any:
    """The genome of a blob: a (G,) float64 array for the float codecs, JSON for ``json``, text."""
    if codec == "json":
        return stored_json(blob, "genome")
    if codec in TEXT_CODECS:
        try:
            return blob.decode("utf-8")
        except UnicodeDecodeError:
            raise StoreError(f"a {codec} genome blob is not UTF-8 text") from None
    dtype = _dtype(codec)
    if len(blob) % dtype.itemsize:
        raise StoreError(f"a {codec} genome blob of {len(blob)} bytes is truncated")
    return np.frombuffer(blob, dtype=dtype).astype(np.float64)


def _dtype(codec: str) -> np.dtype[Any]:
    if codec not in _FLOAT_DTYPES:
        raise StoreError(f"unknown genome codec {codec!r}; choose from {', '.join(CODECS)}")
    return _FLOAT_DTYPES[codec]
