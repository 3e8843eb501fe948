"""Trees and programs as LISP S-expressions (the paper's Figure 7), and back.

A program prints as ``(list``, then one tree per line, then ``)``, e.g.::

    (list
    (- (ifltz q_base_hinge gx q_neck) (% q_elbow time))
    (* 0.5 root_vx))

Constants print as Python's shortest round-trip repr (``15.4963``,
``-28.4382``), so ``parse_program(format_program(p, pset), pset) == p`` exactly.
The same text, UTF-8 encoded, is the genome codec `GENOME_CODEC`: it names
its terminals, so a stored program can be read back by any run whose
primitive set has them.
"""

from __future__ import annotations

import re

import numpy as np

from sinews.control.gp.primitives import ARITY, CONST, VAR, GPError, PrimitiveSet
from sinews.control.gp.tree import Program, Tree

__all__ = [
    "GENOME_CODEC",
    "decode_program",
    "encode_program",
    "format_program",
    "format_tree",
    "parse_program",
    "parse_tree",
]

GENOME_CODEC = "gp-sexpr/1"
"""Codec name of `encode_program` bytes (UTF-8 S-expression text)."""

_TOKEN = re.compile(r"\(|\)|[^\s()]+")


def format_tree(tree: Tree, pset: PrimitiveSet) -> str:
    """The tree as an S-expression, e.g. ``(+ gx (* 0.5 time))``."""
    parts: list[str] = []
    open_children: list[int] = []
    constants = iter(tree.consts.tolist())
    for code in tree.code.tolist():
        if code == CONST:
            parts.append(repr(next(constants)))
        elif code >= VAR:
            parts.append(pset.symbol(code))
        else:
            parts.append("(" + pset.symbol(code))
            open_children.append(int(ARITY[code]))
            continue
        while open_children:
            open_children[-1] -= 1
            if open_children[-1]:
                break
            open_children.pop()
            parts[-1] += ")"
    return " ".join(parts)


def format_program(program: Program, pset: PrimitiveSet) -> str:
    """The program as ``(list``, one tree per line, ``)`` (the paper's Figure 7 layout)."""
    return "(list\n" + "\n".join(format_tree(tree, pset) for tree in program) + ")"


def _tokens(text: str) -> list[str]:
    return _TOKEN.findall(text)


def _read_tree(tokens: list[str], at: int, pset: PrimitiveSet) -> tuple[Tree, int]:
    """The tree starting at ``tokens[at]`` and the index after it."""
    codes: list[int] = []
    consts: list[float] = []
    pending: list[int] = []  # per open function: arguments still to read
    i = at
    while True:
        token = _token(tokens, i)
        i += 1
        if token == "(":
            symbol = _token(tokens, i)
            i += 1
            code = pset.code_of(symbol)
            if code is None or code >= CONST:
                raise GPError(f"{symbol!r} is not a function of this primitive set")
            codes.append(code)
            pending.append(int(ARITY[code]))
            continue
        if token == ")":
            raise GPError("unexpected ')': a function has the wrong number of arguments")
        code = pset.code_of(token)
        if code is None:
            codes.append(CONST)
            consts.append(_number(token))
        elif code < CONST:
            raise GPError(f"function {token!r} must follow an opening parenthesis")
        else:
            codes.append(code)
        while pending:  # a subtree is complete: close every function it completes
            pending[-1] -= 1
            if pending[-1]:
                break
            if _token(tokens, i) != ")":
                raise GPError("a function has the wrong number of arguments")
            i += 1
            pending.pop()
        else:
            return Tree(np.array(codes), np.array(consts)), i


def _token(tokens: list[str], i: int) -> str:
    if i >= len(tokens):
        raise GPError("the expression ends too early")
    return tokens[i]


def _number(token: str) -> float:
    try:
        return float(token)
    except ValueError:
        raise GPError(f"unknown terminal {token!r}") from None


def parse_tree(text: str, pset: PrimitiveSet) -> Tree:
    """Parse one tree written by `format_tree` (any whitespace).

    Raises:
        GPError: unknown symbols, wrong argument counts or trailing text.
    """
    tokens = _tokens(text)
    tree, end = _read_tree(tokens, 0, pset)
    if end != len(tokens):
        raise GPError("text after the end of the tree")
    return tree


def parse_program(text: str, pset: PrimitiveSet) -> Program:
    """Parse a ``(list ...)`` program written by `format_program`.

    Raises:
        GPError: not a list of at least one well-formed tree.
    """
    tokens = _tokens(text)
    if tokens[:2] != ["(", "list"] or tokens[-1:] != [")"]:
        raise GPError("a program must be written (list tree ...)")
    trees: list[Tree] = []
    at = 2
    while at < len(tokens) - 1:
        tree, at = _read_tree(tokens, at, pset)
        trees.append(tree)
    if not trees or at != len(tokens) - 1:
        raise GPError("a program must be written (list tree ...)")
    return tuple(trees)


def encode_program(program: Program, pset: PrimitiveSet) -> bytes:
    """The program as `GENOME_CODEC` bytes."""
    return format_program(program, pset).encode("utf-8")


def decode_program(data: bytes, pset: PrimitiveSet) -> Program:
    """The program from `encode_program` bytes.

    Raises:
        GPError: not UTF-8 or not a program of this primitive set.
    """
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        raise GPError("not a GP program (not UTF-8)") from None
    return parse_program(text, pset)
