"""Spring-net controllers for the figures (seed 001): settings, simulate, score, run."""
