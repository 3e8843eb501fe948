"""The primitive set of a GP run: its functions, named terminals and random constants.

Every node of a tree is one int32 code:

- ``0 .. 9`` a function (`FUNCTIONS`: ``+ - * % ifltz cos sin abs min max``),
- ``CONST`` an ephemeral random constant, whose value is the tree's next
  constant in prefix order,
- ``VAR + k`` the terminal ``pset.terminals[k]`` (column k of the input array).

The function table is a fixed part of the language (the interpreter knows each
opcode); a `PrimitiveSet`, built per run, chooses which functions are in play
and names the terminals. Nothing is registered globally.

Semantics (all float64): ``%`` is protected division, returning 1 when the
divisor's magnitude is below `DIVISION_EPSILON` (Koza's rule, as in the paper);
``(ifltz a b c)`` is ``b`` if ``a < 0`` else ``c`` (a NaN ``a`` selects ``c``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from sinews.errors import SinewsError

__all__ = [
    "ARITY",
    "BASIC_FUNCTIONS",
    "CONST",
    "DIVISION_EPSILON",
    "EXTRA_FUNCTIONS",
    "FUNCTIONS",
    "VAR",
    "GPError",
    "PrimitiveSet",
    "arities",
]

IntArray = npt.NDArray[np.int32]

ADD, SUB, MUL, DIV, IFLTZ, COS, SIN, ABS, MIN, MAX = range(10)
CONST = 10
VAR = 11

DIVISION_EPSILON = 1e-9
"""``(% a b)`` is 1 when ``|b| < DIVISION_EPSILON``."""

FUNCTIONS: dict[str, tuple[int, int]] = {
    "+": (ADD, 2),
    "-": (SUB, 2),
    "*": (MUL, 2),
    "%": (DIV, 2),
    "ifltz": (IFLTZ, 3),
    "cos": (COS, 1),
    "sin": (SIN, 1),
    "abs": (ABS, 1),
    "min": (MIN, 2),
    "max": (MAX, 2),
}
"""Symbol → (opcode, arity) of every function the interpreter knows."""

BASIC_FUNCTIONS = ("+", "-", "*", "%", "ifltz")
"""The paper's function set."""

EXTRA_FUNCTIONS = ("cos", "sin", "abs", "min", "max")
"""Functions a run may add ("cos ... could aid in generation of internal oscillators")."""

ARITY = np.zeros(VAR, dtype=np.int32)
"""(VAR,) arity of each non-variable code (0 for CONST)."""
for _opcode, _arity in FUNCTIONS.values():
    ARITY[_opcode] = _arity
ARITY.flags.writeable = False

_SYMBOLS = {opcode: symbol for symbol, (opcode, _) in FUNCTIONS.items()}
_RESERVED = {"list", *FUNCTIONS}


class GPError(SinewsError):
    """A malformed tree, program or primitive set, or text that does not parse."""


def arities(code: IntArray) -> IntArray:
    """(n,) arity of each node of a code array (terminals and constants: 0)."""
    return np.where(code < VAR, ARITY[np.minimum(code, CONST)], 0).astype(np.int32)


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


@dataclass(frozen=True)
class PrimitiveSet:
    """The functions and terminals trees are built from, for one run.

    Attributes:
        terminals: names of the input columns, in column order (e.g. sensor
            names, ``"time"``, a goal-relative ``"gx"``).
        functions: symbols of the functions in play (see `FUNCTIONS`).
        erc_range: ephemeral random constants are uniform in [lo, hi).
        erc_decimals: constants are rounded to this many decimals (None: not
            rounded); the paper's programs show four.
    """

    terminals: tuple[str, ...]
    functions: tuple[str, ...] = BASIC_FUNCTIONS
    erc_range: tuple[float, float] = (-1.0, 1.0)
    erc_decimals: int | None = 4

    def __post_init__(self) -> None:
        object.__setattr__(self, "terminals", tuple(self.terminals))
        object.__setattr__(self, "functions", tuple(self.functions))
        object.__setattr__(self, "erc_range", tuple(float(v) for v in self.erc_range))
        unknown = [f for f in self.functions if f not in FUNCTIONS]
        if unknown or not self.functions:
            raise GPError(f"unknown function {unknown[0]!r}" if unknown else "no functions")
        if len(set(self.functions)) != len(self.functions):
            raise GPError("a function is listed twice")
        if len(set(self.terminals)) != len(self.terminals):
            raise GPError("a terminal is listed twice")
        for name in self.terminals:
            if (
                not name
                or name in _RESERVED
                or _is_number(name)
                or any(c in name for c in "() \t\n")
            ):
                raise GPError(f"{name!r} cannot name a terminal")
        lo, hi = self.erc_range
        if len(self.erc_range) != 2 or not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
            raise GPError(f"erc_range must be two finite numbers lo < hi, got {self.erc_range}")

    @property
    def function_codes(self) -> IntArray:
        """(F,) opcodes of the functions in play."""
        return np.array([FUNCTIONS[f][0] for f in self.functions], dtype=np.int32)

    @property
    def n_terminals(self) -> int:
        """Number of named terminals V (columns of the input array)."""
        return len(self.terminals)

    def symbol(self, code: int) -> str:
        """The name a node code prints as (constants print their value instead)."""
        if code >= VAR:
            return self.terminals[code - VAR]
        if code == CONST:
            raise GPError("a constant has no symbol; print its value")
        return _SYMBOLS[code]

    def code_of(self, token: str) -> int | None:
        """The code of a function symbol or terminal name in play, else None."""
        if token in self.functions:
            return FUNCTIONS[token][0]
        if token in self.terminals:
            return VAR + self.terminals.index(token)
        return None

    def check(self, code: IntArray) -> None:
        """Raise `GPError` if a code is not a function in play, a constant or a terminal."""
        allowed = np.zeros(VAR + self.n_terminals, dtype=bool)
        allowed[self.function_codes] = True
        allowed[CONST:] = True
        if code.size and (code.min() < 0 or code.max() >= len(allowed) or not allowed[code].all()):
            raise GPError("the tree uses a primitive this primitive set does not have")

    def erc(self, rng: np.random.Generator, n: int | None = None) -> Any:
        """Draw ephemeral random constant(s): a float, or (n,) floats."""
        values = rng.uniform(*self.erc_range, size=n)
        return values if self.erc_decimals is None else np.round(values, self.erc_decimals)

    def to_dict(self) -> dict[str, Any]:
        """A JSON-safe description (see `from_dict`)."""
        return {
            "terminals": list(self.terminals),
            "functions": list(self.functions),
            "erc_range": list(self.erc_range),
            "erc_decimals": self.erc_decimals,
        }

    @classmethod
    def from_dict(cls, doc: Mapping[str, Any]) -> PrimitiveSet:
        """Parse `to_dict` output; raise `GPError` when malformed."""
        try:
            decimals = doc["erc_decimals"]
            return cls(
                terminals=tuple(str(t) for t in doc["terminals"]),
                functions=tuple(str(f) for f in doc["functions"]),
                erc_range=_pair(doc["erc_range"]),
                erc_decimals=None if decimals is None else int(decimals),
            )
        except (KeyError, TypeError, ValueError):
            raise GPError("malformed primitive set description") from None


def _pair(values: Sequence[Any]) -> tuple[float, float]:
    lo, hi = values
    return float(lo), float(hi)
