"""The studio: breed dancers to music in the browser (interactive evolution, Picbreeder-style).

``sinews studio`` starts a local web app (Starlette + uvicorn, 127.0.0.1 by
default) whose page shows a generation of dancers dancing in sync to a song;
a person picks favourites and breeds the next generation. Layout:

- `service` — the studio's state and the single worker thread it lives on;
- `runs` — interactive dancer runs in the run store (create, breed, branch, tempo);
- `motion` — generations and stage dancers danced and packed for the page;
- `live` and `live_socket` — the stage dancer stepped live while a node is dragged;
- `scene_live` and `scene_socket` — the seed-000 scenes played live at 60 fps (the
  ``/scenes`` page);
- `figure_runs`, `figure_motion`, `figure_jobs`, `figure_api` — the ``/figures`` page:
  spring-net and GP figure runs shown as pose packs, picked, bred and evolved in the
  background (docs/figure-studio.md);
- `songs` — demo and uploaded songs, known by generated ids;
- `exports` — genome JSON, GIF, MP4 with sound, contact sheets;
- `pack` — the binary format motion travels in;
- `api`, `validate`, `app`, `server` — routes, request checks, the ASGI app, startup;
- ``static/`` — the page: plain JS modules and a canvas, no build step, no CDN.

The web parts need the ``studio`` extra (``pip install 'sinews[studio]'``).
"""

from __future__ import annotations

from sinews.studio.service import StudioSettings

__all__ = ["StudioSettings"]
