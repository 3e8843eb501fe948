"""Dancers evolved to a song (seed 000): settings, simulate, score, run."""
