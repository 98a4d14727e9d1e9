"""Worker processes draw with OSMesa in their own thread unless told otherwise."""

import os

from homesim.processes import RASTER_THREADS, rasterize_in_drawing_thread


def test_a_worker_rasterizes_in_its_drawing_thread_unless_told_otherwise(monkeypatch):
    monkeypatch.delenv("LP_NUM_THREADS", raising=False)
    rasterize_in_drawing_thread()
    assert os.environ["LP_NUM_THREADS"] == RASTER_THREADS == "0"
    monkeypatch.setenv("LP_NUM_THREADS", "3")
    rasterize_in_drawing_thread()
    assert os.environ["LP_NUM_THREADS"] == "3"
