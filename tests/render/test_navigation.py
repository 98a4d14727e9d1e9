import itertools

import numpy as np

from homesim.render.layout import build_layout, to_mujoco
from homesim.render.navigation import CELL, build_grid, plan_path


def test_grid_blocks_furniture_and_keeps_floor(box_home):
    grid = build_grid(build_layout(box_home))
    assert not grid.free[grid.cell((1.0, -1.0))]  # the table
    assert grid.free[grid.cell((0.0, 0.0))]  # the middle of the room
    assert not grid.free[grid.cell((1.94, 0.0))]  # next to a wall


def test_path_goes_around_the_table_and_ends_within_reach(box_home):
    layout = build_layout(box_home)
    grid = build_grid(layout)
    tv = to_mujoco(box_home.node(22))
    start = grid.point(grid.nearest_free((1.0, -1.7)))  # behind the table, seen from the TV
    path = plan_path(grid, start, tv, reach=0.7)
    for a, b in itertools.pairwise(path):
        assert grid.line_free(a, b)
    end = path[-1]
    gap = np.maximum(np.abs(end - tv.center[:2]) - tv.half[:2], 0.0)
    assert np.hypot(*gap) <= 0.7 + CELL


def test_paths_through_doors_in_a_real_apartment(shared_data):
    from homesim.world.homes import load_home

    g = load_home("scene1")
    layout = build_layout(g)
    grid = build_grid(layout)
    path = plan_path(grid, layout.start, to_mujoco(g.node(410)))  # bedroom -> living room tv
    assert len(path) >= 3
    length = sum(np.linalg.norm(b - a) for a, b in itertools.pairwise(path))
    assert 8.0 < length < 30.0
