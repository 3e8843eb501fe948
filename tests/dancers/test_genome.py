"""Dancer genome: layout, JSON round trip, and validation that names the field."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from sinews.dancers import EDGE_NAMES, NODES, DancerGenome, GenomeError
from sinews.dancers.genome import BODY_GENES, SCHEMA_VERSION


def test_layout_has_every_section() -> None:
    genome = DancerGenome.random(np.random.default_rng(0))
    assert set(genome.body) == set(BODY_GENES)
    assert {"stiffness", "bulkiness", "lankiness", "torso_triangularity"} <= set(genome.body)
    assert genome.nodes.shape == (len(NODES), 4)
    assert genome.edges.shape == (len(EDGE_NAMES), 3)
    assert genome.responders.shape == (len(NODES), 2, 5)
    assert genome.values.size == DancerGenome.SIZE


def test_values_are_read_only_and_in_range() -> None:
    genome = DancerGenome.random(np.random.default_rng(1))
    with pytest.raises(ValueError, match="read-only"):
        genome.values[0] = 0.3
    with pytest.raises(GenomeError, match=r"\[0, 1\]"):
        DancerGenome(np.full(DancerGenome.SIZE, 1.2))
    with pytest.raises(GenomeError, match="values"):
        DancerGenome(np.zeros(3))


def test_json_round_trip_is_exact(tmp_path: Path) -> None:
    genome = DancerGenome.random(np.random.default_rng(2))
    path = genome.save(tmp_path / "d.json")
    again = DancerGenome.load(path)
    assert again == genome
    doc = json.loads(path.read_text())
    assert doc["kind"] == "sinews.dancer" and doc["schema_version"] == SCHEMA_VERSION
    assert doc["edges"]["head-neck"].keys() == {"length", "strength", "easing"}


def test_replace_changes_only_the_named_gene() -> None:
    genome = DancerGenome.neutral()
    stiff = genome.replace(stiffness=0.9)
    assert stiff.body["stiffness"] == 0.9
    assert np.count_nonzero(stiff.values != genome.values) == 1
    with pytest.raises(GenomeError, match="wobble"):
        genome.replace(wobble=0.1)


def _doc() -> dict[str, Any]:
    return DancerGenome.random(np.random.default_rng(3)).to_dict()


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        (lambda d: d["body"].update(stiffness=1.5), r"body\.stiffness: 1\.5 is outside \[0, 1\]"),
        (lambda d: d["body"].update(stiffness="soft"), r"body\.stiffness: must be a number"),
        (lambda d: d["body"].update(stiffness=True), r"body\.stiffness: must be a number"),
        (lambda d: d["body"].pop("lankiness"), r"body\.lankiness: missing"),
        (lambda d: d["body"].update(wobble=0.2), r"body\.wobble: unknown field"),
        (lambda d: d["nodes"]["l_hand"].update(radius=-0.1), r"nodes\.l_hand\.radius: -0\.1"),
        (lambda d: d["nodes"].pop("head"), r"nodes\.head: missing"),
        (lambda d: d["edges"]["head-neck"].pop("easing"), r"edges\.head-neck\.easing: missing"),
        (lambda d: d["responders"]["head"].pop(), r"responders\.head: must be a list of 2"),
        (
            lambda d: d["responders"]["r_foot"][1].update(pitch=2),
            r"responders\.r_foot\[1\]\.pitch: 2 is outside",
        ),
        (lambda d: d.update(kind="sinews.kitten"), r"kind: expected"),
        (lambda d: d.update(schema_version=99), r"schema_version: 99 is newer"),
        (lambda d: d.pop("edges"), r"^edges: missing"),
        (lambda d: d.update(extra=1), r"^extra: unknown field"),
    ],
)
def test_bad_documents_name_the_field(edit: Any, message: str) -> None:
    doc = _doc()
    edit(doc)
    with pytest.raises(GenomeError, match=message):
        DancerGenome.from_dict(doc)


def test_nan_and_infinity_in_files_are_rejected(tmp_path: Path) -> None:
    text = json.dumps(_doc()).replace('"stiffness": ', '"stiffness": NaN, "x": ', 1)
    path = tmp_path / "nan.json"
    path.write_text(text)
    with pytest.raises(GenomeError, match="NaN is not allowed"):
        DancerGenome.load(path)


@pytest.mark.parametrize(
    ("content", "message"),
    [
        (b"{not json", "not valid JSON"),
        (b"[1, 2, 3]", "genome: must be an object"),
        (b"\xff\xfe\x00binary", "cannot read"),
    ],
)
def test_bad_files_give_one_line_errors(tmp_path: Path, content: bytes, message: str) -> None:
    path = tmp_path / "bad.json"
    path.write_bytes(content)
    with pytest.raises(GenomeError, match=message) as info:
        DancerGenome.load(path)
    assert "\n" not in str(info.value) and str(path) in str(info.value)


def test_missing_file(tmp_path: Path) -> None:
    with pytest.raises(GenomeError, match="cannot read"):
        DancerGenome.load(tmp_path / "nope.json")
