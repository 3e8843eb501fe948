"""sinews: evolve expressive motion.

Spring-mass dancers that move to music (Teuhana), spring-net controllers and
genetic-programming controllers for articulated figures.
"""

from __future__ import annotations

__version__ = "0.1.0"
__all__ = ["__version__"]
