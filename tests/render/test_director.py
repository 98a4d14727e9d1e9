from types import SimpleNamespace

import numpy as np

from homesim.render.cameras import CameraSpec
from homesim.render.director import MIN_HOLD, Director
from homesim.render.layout import Box, Layout


def _scene():
    room = Box(np.array([0.0, 0.0, 0.0]), np.array([2.0, 2.0, 0.0]))
    layout = Layout([], {1: room}, {1: "livingroom"}, [room], {1: room}, np.zeros(2))
    cams = [CameraSpec(f"c{i}", 1, np.array([i, 0.0, 2.0]), np.array([1.0, 0, 0]),
                       np.array([0, 0, 1.0]), 60.0) for i in range(3)]
    return SimpleNamespace(layout=layout, cameras=cams)


def test_picks_the_best_view_then_keeps_it_while_it_is_good():
    d = Director(_scene())
    scores = {0: 0.5, 1: 1.9, 2: 1.0}
    agent = np.array([0.0, 0.0, 1.0])
    assert d.choose(agent, None, scores.get) == 1
    scores[2] = 2.5  # a better view appears, but the current one is still good
    for _ in range(MIN_HOLD + 5):
        assert d.choose(agent, 1.8, scores.get) == 1


def test_cuts_when_the_agent_is_lost():
    d = Director(_scene())
    agent = np.array([0.0, 0.0, 1.0])
    assert d.choose(agent, None, {0: 1.5, 1: 0.2, 2: 0.1}.get) == 0
    assert d.choose(agent, 0.0, {0: 0.0, 1: 0.2, 2: 1.2}.get) == 2  # lost: cut at once
