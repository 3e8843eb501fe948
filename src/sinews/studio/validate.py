"""Checking what requests send: JSON bodies and query values, with one-line 4xx errors."""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from typing import Any

from starlette.requests import Request

from sinews import safe_json
from sinews.errors import SinewsError

__all__ = [
    "MAX_JSON_BYTES",
    "RequestError",
    "body_fields",
    "flag",
    "json_object",
    "number",
    "parse_whole",
    "point",
    "unit_values",
    "whole",
]

MAX_JSON_BYTES = 64 * 1024


class RequestError(SinewsError):
    """A malformed request; ``status`` is the HTTP status to answer with."""

    def __init__(self, message: str, status: int = 400) -> None:
        super().__init__(message)
        self.status = status


async def body_fields(
    request: Request, required: Iterable[str], optional: Iterable[str] = ()
) -> dict[str, Any]:
    """The request's JSON object, with exactly the allowed fields.

    Raises:
        RequestError: not ``application/json`` (415), too large (413), not a
            JSON object, a missing or an unknown field (400).
    """
    if request.headers.get("content-type", "").split(";")[0].strip() != "application/json":
        raise RequestError("send the request body as application/json", 415)
    raw = b""
    async for chunk in request.stream():
        raw += chunk
        if len(raw) > MAX_JSON_BYTES:
            raise RequestError(f"request body larger than {MAX_JSON_BYTES // 1024} KB", 413)
    body = _parse(raw or b"null", "request body")
    if not isinstance(body, dict):
        raise RequestError("request body must be a JSON object")
    needed, allowed = set(required), set(required) | set(optional)
    missing = sorted(needed - set(body))
    if missing:
        raise RequestError(f"missing field {missing[0]!r}")
    unknown = sorted(set(body) - allowed)
    if unknown:
        raise RequestError(f"unknown field {unknown[0]!r}")
    return body


def json_object(message: str | Mapping[str, Any]) -> dict[str, Any]:
    """A websocket message: a JSON object of at most `MAX_JSON_BYTES` characters.

    Args:
        message: the text, or the ASGI ``websocket.receive`` message holding it.

    Raises:
        RequestError: binary, too long, not JSON, or not an object.
    """
    if not isinstance(message, str):
        if message.get("text") is None:
            raise RequestError("messages must be JSON text")
        message = str(message["text"])
    if len(message) > MAX_JSON_BYTES:
        raise RequestError(f"messages must be shorter than {MAX_JSON_BYTES // 1024} KB")
    request = _parse(message, "messages must be JSON")
    if not isinstance(request, dict):
        raise RequestError("messages must be JSON objects")
    return request


def _parse(text: str | bytes, what: str) -> Any:
    """JSON within `safe_json`'s bounds (digits, depth, no NaN); `RequestError` otherwise."""
    try:
        return safe_json.loads(text)
    except SinewsError as exc:
        raise RequestError(f"{what}: {exc}") from None


def number(value: object, name: str, lo: float, hi: float) -> float:
    """A JSON number in [lo, hi]."""
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise RequestError(f"{name} must be a number")
    if not lo <= value <= hi:
        raise RequestError(f"{name} must be in [{lo:g}, {hi:g}], got {value:g}")
    return float(value)


def whole(value: object, name: str, lo: int, hi: int) -> int:
    """A JSON integer in [lo, hi]."""
    if isinstance(value, bool) or not isinstance(value, int):
        raise RequestError(f"{name} must be a whole number")
    if not lo <= value <= hi:
        raise RequestError(f"{name} must be in [{lo}, {hi}], got {value}")
    return value


def flag(value: object, name: str) -> bool:
    """A JSON boolean."""
    if not isinstance(value, bool):
        raise RequestError(f"{name} must be true or false")
    return value


def point(value: object, name: str, limit: float) -> tuple[float, float]:
    """A JSON pair [x, y] of numbers, each within ±``limit``."""
    if not isinstance(value, list) or len(value) != 2:
        raise RequestError(f"{name} must be a pair [x, y]")
    x, y = value
    return (number(x, f"{name} x", -limit, limit), number(y, f"{name} y", -limit, limit))


def parse_whole(text: str, name: str, lo: int, hi: int) -> int:
    """An integer in [lo, hi] written in a path or query."""
    if not text.isascii() or not text.isdigit() or len(text) > len(str(hi)):
        raise RequestError(f"{name} must be a whole number from {lo} to {hi}")
    return whole(int(text), name, lo, hi)


def unit_values(values: Mapping[str, str], names: Iterable[str]) -> dict[str, float]:
    """The given ones of ``names`` from a query, each a number in [0, 1]; others are refused."""
    allowed = set(names)
    unknown = sorted(set(values) - allowed)
    if unknown:
        raise RequestError(f"unknown parameter {unknown[0]!r}")
    found = {}
    for name, text in values.items():
        try:
            value = float(text)
        except ValueError:
            raise RequestError(f"{name} must be a number") from None
        found[name] = number(value, name, 0.0, 1.0)
    return found
