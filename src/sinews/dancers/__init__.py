"""Teuhana's dancers: the genome, its development into a tensegrity humanoid."""

from __future__ import annotations

from sinews.dancers.develop import DANCER_ENGINE, develop
from sinews.dancers.genome import DancerGenome, GenomeError
from sinews.dancers.skeleton import EDGE_NAMES, NODES

__all__ = ["DANCER_ENGINE", "EDGE_NAMES", "NODES", "DancerGenome", "GenomeError", "develop"]
