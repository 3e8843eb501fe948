"""GP controller programs for the figures' tasks (seed 003): settings, simulate, score, run."""
