"""Run kinds: what evolves, how it is scored, and the resumable loop they share.

Layout (each kind has the same four modules):

- ``kinds`` — the `RunKind` protocol and the registry the CLI and the studio use.
- ``evolution`` — the loop: ask, score, store, tell; resumable bit for bit.
- ``run_config`` — run files and options merged into the common settings.
- ``score_memory`` — scoring in chunks on an evaluator, without re-simulating survivors.
- ``figures`` — what the figure kinds share (the built-in figures, keep files).
- ``dancers/``, ``springnet/``, ``gp/`` — ``settings`` (one dataclass or config
  reader), ``simulate``, ``score`` and ``run`` (the kind itself, ``KIND``).
"""
