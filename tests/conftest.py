"""Shared test builders: a tiny home, the shared apartments and the real data set."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from homesim.world.graph import EnvironmentGraph

SHARED_DATA = Path(__file__).resolve().parents[1].parent / "shared" / "data" / "virtualhome"


def tiny_home_dict() -> dict:
    """A kitchen and a living room: character, closed fridge with a cup, table, TV, sofa."""
    nodes = [
        {"id": 1, "class_name": "kitchen", "category": "Rooms"},
        {"id": 2, "class_name": "living_room", "category": "Rooms"},
        {"id": 10, "class_name": "character", "category": "Characters"},
        {"id": 11, "class_name": "fridge", "properties": ["CAN_OPEN", "CONTAINERS"],
         "states": ["CLOSED"]},
        {"id": 12, "class_name": "cup", "properties": ["GRABBABLE", "RECIPIENT"]},
        {"id": 13, "class_name": "table", "properties": ["SURFACES"]},
        {"id": 14, "class_name": "tv", "properties": ["HAS_SWITCH", "LOOKABLE"],
         "states": ["OFF"]},
        {"id": 15, "class_name": "sofa", "properties": ["SITTABLE", "LIEABLE"]},
        {"id": 16, "class_name": "plate", "properties": ["GRABBABLE", "RECIPIENT"]},
    ]
    edges = [
        (10, "INSIDE", 1), (11, "INSIDE", 1), (12, "INSIDE", 11), (12, "INSIDE", 1),
        (13, "INSIDE", 1), (16, "ON", 13), (16, "INSIDE", 1),
        (14, "INSIDE", 2), (15, "INSIDE", 2), (15, "FACING", 14),
        # VirtualHome graphs make what is in or on something CLOSE to it, both ways.
        (12, "CLOSE", 11), (11, "CLOSE", 12), (16, "CLOSE", 13), (13, "CLOSE", 16),
    ]
    return {"nodes": nodes,
            "edges": [{"from_id": a, "relation_type": r, "to_id": b} for a, r, b in edges]}


@pytest.fixture
def tiny_home() -> EnvironmentGraph:
    return EnvironmentGraph.from_dict(tiny_home_dict())


@pytest.fixture(scope="session")
def shared_data() -> Path:
    if not SHARED_DATA.is_dir():
        pytest.skip(f"shared data not found at {SHARED_DATA} (see the README: seven tests "
                    "need ../shared/data/virtualhome)")
    return SHARED_DATA


@pytest.fixture(scope="session")
def real_data():
    """The fetched real program data set; fails instead of skipping under make test."""
    from homesim.knowledge.fetch import dataset_dir, is_fetched

    if not is_fetched():
        message = f"real data set not fetched at {dataset_dir()} (run 'homesim data fetch')"
        if os.environ.get("HOMESIM_REQUIRE_DATA"):
            pytest.fail(message)
        pytest.skip(message)
    return dataset_dir()


@pytest.fixture(autouse=True)
def _no_leftover_cli_children():
    """After each test, kill any `homesim` child process it left running."""
    yield
    from tests.cli.subprocess_cli import kill_leftover_children

    kill_leftover_children()


WRITER_ACTIVITIES = ("Watch TV", "Turn on light", "Drink", "Read book")
"""The activities the small program writer of the tests is fitted on."""


@pytest.fixture(scope="session")
def small_writer(real_data):
    """A program writer fitted on the real programs of `WRITER_ACTIVITIES` (seconds, where
    all 518 take half a minute)."""
    pytest.importorskip("sklearn")
    from homesim.learn.data import real_examples
    from homesim.learn.rerank.program_writer import ProgramWriter

    examples = [e for e in real_examples(real_data) if e.title in WRITER_ACTIVITIES]
    return ProgramWriter.fit(examples)
