"""Binary packs: a JSON header and typed arrays in one response, read by ``static/js/pack.js``.

Trajectories travel to the page as typed arrays, not JSON (REFERENCE.md:
20 dancers x 600 frames as JSON are 5x larger and take 20x longer to fetch
and parse). A pack is::

    b"SNWP" | uint32 little-endian header length H | H bytes of UTF-8 JSON | arrays

The header holds the caller's fields plus ``"arrays"``: for each array its
``dtype``, ``shape`` and ``offset`` (bytes from the end of the header). The
header is padded with spaces and every array starts at a multiple of 8
bytes, so the page can view each one in place (``new Int16Array(buffer,
offset, length)``) without copying.

Motion is sent in int16 millimetres (half the size of float32; ±32.7 m is
far more room than a dancer needs, positions beyond are clipped).
"""

from __future__ import annotations

import json
import struct
from collections.abc import Mapping
from typing import Any

import numpy as np
import numpy.typing as npt

__all__ = ["MAGIC", "MEDIA_TYPE", "MILLIMETRES", "encode_pack", "millimetres"]

MAGIC = b"SNWP"
MEDIA_TYPE = "application/octet-stream"
MILLIMETRES = 0.001
"""Metres per unit of an int16 millimetre array (the header's ``scale``)."""

_DTYPES = {
    np.dtype(np.int16): "int16",
    np.dtype(np.float32): "float32",
    np.dtype(np.uint8): "uint8",
    np.dtype(np.int32): "int32",
}
_ALIGN = 8
_INT16_MAX = np.iinfo(np.int16).max


def millimetres(metres: npt.ArrayLike) -> npt.NDArray[np.int16]:
    """Metres → int16 millimetres, rounded, clipped to ±32.767 m; NaN becomes 0."""
    values = np.asarray(metres, dtype=np.float32) * np.float32(1.0 / MILLIMETRES)
    np.nan_to_num(values, copy=False)
    np.clip(values, -_INT16_MAX, _INT16_MAX, out=values)
    return np.rint(values, out=values).astype(np.int16)


def encode_pack(header: Mapping[str, Any], arrays: Mapping[str, npt.NDArray[Any]]) -> bytes:
    """One pack of ``header`` (JSON-safe values) and little-endian ``arrays``.

    Args:
        header: fields for the page; must not use the key ``"arrays"``.
        arrays: by name; dtypes int16, float32, uint8 or int32 (bool is sent as uint8).

    Returns:
        The pack's bytes.
    """
    if "arrays" in header:
        raise ValueError("the header key 'arrays' is reserved")
    table: dict[str, dict[str, Any]] = {}
    blobs: list[bytes] = []
    offset = 0
    for name, array in arrays.items():
        values = np.ascontiguousarray(array.astype(np.uint8) if array.dtype == bool else array)
        dtype = _DTYPES.get(values.dtype)
        if dtype is None:
            raise ValueError(f"array {name!r}: dtype {values.dtype} cannot be packed")
        data = values.astype(values.dtype.newbyteorder("<"), copy=False).tobytes()
        table[name] = {"dtype": dtype, "shape": list(values.shape), "offset": offset}
        blobs.append(data + b"\0" * (-len(data) % _ALIGN))
        offset += len(blobs[-1])
    text = json.dumps({**header, "arrays": table}, separators=(",", ":"), allow_nan=False)
    head = text.encode()
    head += b" " * (-(len(MAGIC) + 4 + len(head)) % _ALIGN)
    return b"".join([MAGIC, struct.pack("<I", len(head)), head, *blobs])
