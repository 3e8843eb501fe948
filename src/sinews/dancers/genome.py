"""The dancer genome (seed 000, Fig. 6): floats in [0, 1], saved as versioned JSON.

The genome is one flat vector (what the evolution works on) with named views:
main body modifiers, per-node modifiers, per-edge modifiers, and two dance
responder slots per node. 0.5 is the neutral value of every modifier.
"""

from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from sinews import safe_json
from sinews.dancers.skeleton import EDGE_NAMES, NODES
from sinews.errors import SinewsError
from sinews.files import write_text

__all__ = [
    "BODY_GENES",
    "EDGE_GENES",
    "GENOME_KIND",
    "NODE_GENES",
    "RESPONDER_GENES",
    "RESPONDER_SLOTS",
    "SCHEMA_VERSION",
    "DancerGenome",
    "GenomeError",
]

GENOME_KIND = "sinews.dancer"
SCHEMA_VERSION = 1

BODY_GENES: dict[str, str] = {
    "stiffness": "how hard every spring pulls back",
    "bulkiness": "node size and mass, torso width",
    "lankiness": "limb length relative to the torso",
    "torso_triangularity": "0 narrow shoulders and wide hips, 1 broad shoulders and narrow hips",
    "height": "standing height, 1.5 to 1.9 m",
    "head_size": "head radius",
    "arm_spread": "rest angle of the arms away from the body",
    "stance": "how far apart the feet stand",
    "drag": "velocity lost per frame: slippery to sticky",
    "groundedness": "pull toward the rest pose (home force)",
    "jitter": "amplitude of the wiggle force",
    "hue": "base colour",
    "colorfulness": "how far node colours spread around the base hue",
}
"""Main body modifiers and what each shapes."""

NODE_GENES: tuple[str, ...] = ("radius", "density", "dx", "dy")
EDGE_GENES: tuple[str, ...] = ("length", "strength", "easing")
RESPONDER_GENES: tuple[str, ...] = ("species", "strength", "pitch", "width", "custom")
RESPONDER_SLOTS = 2

_N_BODY = len(BODY_GENES)
_N_NODES = len(NODES) * len(NODE_GENES)
_N_EDGES = len(EDGE_NAMES) * len(EDGE_GENES)
_N_RESP = len(NODES) * RESPONDER_SLOTS * len(RESPONDER_GENES)
_SECTIONS = np.cumsum([0, _N_BODY, _N_NODES, _N_EDGES, _N_RESP])


class GenomeError(SinewsError):
    """A genome (or genome file) that is malformed or out of range."""


@dataclass(frozen=True, eq=False)
class DancerGenome:
    """A dancer's DNA: a flat vector of floats in [0, 1].

    Attributes:
        values: (G,) float64 in [0, 1]; see `body`, `nodes`, `edges`, `responders`.
    """

    values: npt.NDArray[np.float64]

    SIZE = int(_SECTIONS[-1])

    def __post_init__(self) -> None:
        values = np.array(self.values, dtype=np.float64)
        if values.shape != (self.SIZE,):
            raise GenomeError(f"a dancer genome has {self.SIZE} values, got {values.shape}")
        if not np.all(np.isfinite(values)) or values.min() < 0 or values.max() > 1:
            raise GenomeError("every genome value must be a number in [0, 1]")
        values.flags.writeable = False
        object.__setattr__(self, "values", values)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, DancerGenome) and np.array_equal(self.values, other.values)

    __hash__ = None  # type: ignore[assignment]

    @classmethod
    def random(cls, rng: np.random.Generator) -> DancerGenome:
        """A genome with every value uniform in [0, 1]."""
        return cls(rng.random(cls.SIZE))

    @classmethod
    def neutral(cls) -> DancerGenome:
        """Every gene 0.5: the average body, no responders."""
        values = np.full(cls.SIZE, 0.5)
        values[_SECTIONS[3] :] = 0.0
        return cls(values)

    @property
    def body(self) -> dict[str, float]:
        """Main body modifiers by name."""
        return dict(zip(BODY_GENES, self.values[: _SECTIONS[1]].tolist(), strict=True))

    @property
    def nodes(self) -> npt.NDArray[np.float64]:
        """(N, 4) per-node modifiers: radius, density, dx, dy (rows follow `NODES`)."""
        return self.values[_SECTIONS[1] : _SECTIONS[2]].reshape(len(NODES), len(NODE_GENES))

    @property
    def edges(self) -> npt.NDArray[np.float64]:
        """(E, 3) per-edge modifiers: length, strength, easing (rows follow `EDGE_NAMES`)."""
        return self.values[_SECTIONS[2] : _SECTIONS[3]].reshape(len(EDGE_NAMES), len(EDGE_GENES))

    @property
    def responders(self) -> npt.NDArray[np.float64]:
        """(N, 2, 5) responder slots: species, strength, pitch, width, custom."""
        return self.values[_SECTIONS[3] :].reshape(
            len(NODES), RESPONDER_SLOTS, len(RESPONDER_GENES)
        )

    def replace(self, **body_genes: float) -> DancerGenome:
        """A copy with some main body modifiers changed (e.g. ``stiffness=0.9``)."""
        values = self.values.copy()
        names = list(BODY_GENES)
        for name, value in body_genes.items():
            if name not in BODY_GENES:
                raise GenomeError(f"no body gene called {name!r}")
            values[names.index(name)] = value
        return DancerGenome(values)

    def to_dict(self) -> dict[str, Any]:
        """The JSON document of this genome."""
        return {
            "kind": GENOME_KIND,
            "schema_version": SCHEMA_VERSION,
            "body": self.body,
            "nodes": {
                name: dict(zip(NODE_GENES, row.tolist(), strict=True))
                for name, row in zip(NODES, self.nodes, strict=True)
            },
            "edges": {
                name: dict(zip(EDGE_GENES, row.tolist(), strict=True))
                for name, row in zip(EDGE_NAMES, self.edges, strict=True)
            },
            "responders": {
                name: [dict(zip(RESPONDER_GENES, slot.tolist(), strict=True)) for slot in slots]
                for name, slots in zip(NODES, self.responders, strict=True)
            },
        }

    @classmethod
    def from_dict(cls, doc: object) -> DancerGenome:
        """Parse and validate a JSON document; errors name the offending field."""
        top = _mapping(doc, "genome")
        _exact_keys(top, {"kind", "schema_version", "body", "nodes", "edges", "responders"}, "")
        if top["kind"] != GENOME_KIND:
            raise GenomeError(f"kind: expected {GENOME_KIND!r}, got {top['kind']!r}")
        version = top["schema_version"]
        if not isinstance(version, int) or isinstance(version, bool) or version < 1:
            raise GenomeError("schema_version: must be a positive integer")
        if version > SCHEMA_VERSION:
            raise GenomeError(
                f"schema_version: {version} is newer than this sinews ({SCHEMA_VERSION})"
            )
        values: list[float] = []
        body = _mapping(top["body"], "body")
        _exact_keys(body, set(BODY_GENES), "body.")
        values += [_unit(body[g], f"body.{g}") for g in BODY_GENES]
        values += _table(top["nodes"], "nodes", NODES, NODE_GENES)
        values += _table(top["edges"], "edges", EDGE_NAMES, EDGE_GENES)
        responders = _mapping(top["responders"], "responders")
        _exact_keys(responders, set(NODES), "responders.")
        for node in NODES:
            slots = responders[node]
            where = f"responders.{node}"
            if not isinstance(slots, list) or len(slots) != RESPONDER_SLOTS:
                raise GenomeError(f"{where}: must be a list of {RESPONDER_SLOTS} slots")
            for k, slot in enumerate(slots):
                values += _row(slot, f"{where}[{k}]", RESPONDER_GENES)
        return cls(np.array(values))

    def save(self, path: str | os.PathLike[str]) -> Path:
        """Write the genome as JSON (atomically) and return the path."""
        path = Path(path)
        try:
            write_text(path, json.dumps(self.to_dict(), indent=1) + "\n")
        except OSError as exc:
            raise GenomeError(f"{path}: cannot write ({exc.strerror})") from None
        return path

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> DancerGenome:
        """Read and validate a genome file; raise `GenomeError` naming the problem."""
        path = Path(path)
        try:
            text = path.read_text()
        except (OSError, UnicodeDecodeError) as exc:
            reason = getattr(exc, "strerror", None) or "not a text file"
            raise GenomeError(f"{path}: cannot read ({reason})") from None
        try:
            doc = safe_json.loads(text)
        except SinewsError as exc:
            raise GenomeError(f"{path}: {exc}") from None
        try:
            return cls.from_dict(doc)
        except GenomeError as exc:
            raise GenomeError(f"{path}: {exc}") from None


def _mapping(value: object, where: str) -> dict[str, Any]:
    if not isinstance(value, dict):
        raise GenomeError(f"{where}: must be an object")
    return value


def _exact_keys(mapping: dict[str, Any], expected: set[str], prefix: str) -> None:
    missing = [k for k in expected if k not in mapping]
    if missing:
        raise GenomeError(f"{prefix}{sorted(missing)[0]}: missing")
    unknown = [k for k in mapping if k not in expected]
    if unknown:
        raise GenomeError(f"{prefix}{sorted(unknown)[0]}: unknown field")


def _unit(value: object, where: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise GenomeError(f"{where}: must be a number in [0, 1]")
    number = float(value)
    if not math.isfinite(number) or not 0.0 <= number <= 1.0:
        raise GenomeError(f"{where}: {value!r} is outside [0, 1]")
    return number


def _row(value: object, where: str, genes: tuple[str, ...]) -> list[float]:
    row = _mapping(value, where)
    _exact_keys(row, set(genes), f"{where}.")
    return [_unit(row[g], f"{where}.{g}") for g in genes]


def _table(value: object, where: str, rows: tuple[str, ...], genes: tuple[str, ...]) -> list[float]:
    table = _mapping(value, where)
    _exact_keys(table, set(rows), f"{where}.")
    return [v for name in rows for v in _row(table[name], f"{where}.{name}", genes)]
