"""JSON from users (genome files, run documents, studio requests) read with bounds.

Python's `json` accepts integers of thousands of digits (converting one to a
float overflows later), nesting deep enough to exhaust the stack, and NaN.
`loads` refuses all three, and documents over `MAX_JSON_BYTES`, with one
`SinewsError` line saying what was wrong.
"""

from __future__ import annotations

import json
from typing import Any

from sinews.errors import SinewsError
from sinews.limits import MAX_JSON_BYTES, MAX_JSON_DEPTH, MAX_JSON_DIGITS

__all__ = ["loads"]


def _integer(text: str) -> int:
    if len(text.lstrip("-")) > MAX_JSON_DIGITS:
        raise SinewsError(f"an integer of {len(text)} digits (at most {MAX_JSON_DIGITS})")
    return int(text)


def _float(text: str) -> float:
    value = float(text)
    if value in (float("inf"), float("-inf")):
        raise SinewsError(f"the number {text[:20]}... is too large")
    return value


def _constant(name: str) -> float:
    raise SinewsError(f"{name} is not allowed")


def _depth(text: str) -> int:
    """Deepest nesting of arrays and objects, brackets inside strings ignored."""
    depth = deepest = 0
    in_string = escaped = False
    for char in text:
        if in_string:
            if escaped:
                escaped = False
            elif char == "\\":
                escaped = True
            elif char == '"':
                in_string = False
        elif char == '"':
            in_string = True
        elif char in "[{":
            depth += 1
            deepest = max(deepest, depth)
            if deepest > MAX_JSON_DEPTH:
                break
        elif char in "]}":
            depth -= 1
    return deepest


def loads(text: str | bytes) -> Any:
    """Parse a JSON document within the limits.

    Raises:
        SinewsError: not JSON, too large, nested deeper than `MAX_JSON_DEPTH`,
            an integer longer than `MAX_JSON_DIGITS`, or NaN/Infinity.
    """
    if len(text) > MAX_JSON_BYTES:
        raise SinewsError(f"document too large ({len(text)} bytes; at most {MAX_JSON_BYTES})")
    if isinstance(text, bytes):
        try:
            text = text.decode("utf-8")
        except UnicodeDecodeError:
            raise SinewsError("not UTF-8 text") from None
    if _depth(text) > MAX_JSON_DEPTH:
        raise SinewsError(f"nested deeper than {MAX_JSON_DEPTH} levels")
    try:
        return json.loads(text, parse_int=_integer, parse_float=_float, parse_constant=_constant)
    except json.JSONDecodeError as exc:
        raise SinewsError(f"not valid JSON (line {exc.lineno}: {exc.msg})") from None
