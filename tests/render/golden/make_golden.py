"""Make the golden inputs and pictures of ``tests/render/test_golden.py``.

Run from the repository root: ``python tests/render/golden/make_golden.py``.
The inputs (a dancer's motion on the groove demo, a spring-net snake's
replay) are saved as ``.npz`` so the pictures test the drawing only, not the
physics. Pictures are made by ``test_golden.picture`` and, for a new golden
set, written over the old ones: only do that when a picture is meant to change.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).parent


def make_inputs() -> None:
    """Simulate the two motions and save them next to this script."""
    from sinews.dancers import DancerGenome
    from sinews.experiments.dancers.simulate import dance
    from sinews.experiments.springnet.settings import SpringNetSettings
    from sinews.experiments.springnet.simulate import simulate
    from sinews.music import analyse
    from sinews.music.decode import Audio
    from sinews.music.demo import demo_song

    song = demo_song("groove")
    music = analyse(Audio(samples=song.samples.mean(axis=1), sample_rate=song.sample_rate))
    genome = DancerGenome.random(np.random.default_rng(14))
    (traj,) = dance([genome], 3.0, music=music, seeds=[5], record_forces=True)
    traj.save(HERE / "dancer.npz")

    settings = SpringNetSettings.from_values({"figure": "snake", "seconds": 3.0, "control_hz": 100})
    genes = np.random.default_rng(14).uniform(size=(1, settings.encoding.size))
    result, net = simulate(settings, genes, record_hz=20.0)
    assert net is not None
    result.trajectory(0).save(HERE / "snake.npz")
    nets = settings.encoding.decode(genes)
    outputs = np.arange(result.figure.n_actuators) % settings.masses
    np.savez_compressed(HERE / "snake_net.npz", positions=net[:, 0], masses=nets.masses[0],
                        springs=nets.springs[0], outputs=outputs,
                        labels=np.array(result.figure.joints))  # fmt: skip


if __name__ == "__main__":
    make_inputs()
    sys.path.insert(0, str(HERE.parent))
    from test_golden import write_pictures

    write_pictures(HERE)
