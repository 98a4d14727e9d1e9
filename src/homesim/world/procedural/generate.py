"""`generate_home`: a new apartment from a seed, checked before it is returned."""

from __future__ import annotations

import random
from pathlib import Path

from homesim.errors import GraphError
from homesim.world.classes import ClassKnowledge, default_kb
from homesim.world.graph import EnvironmentGraph
from homesim.world.procedural.checks import check_home
from homesim.world.procedural.furnish import RoomFurnisher, furnish_room
from homesim.world.procedural.geometry import DOOR_REACH, FreeFloor, blocks
from homesim.world.procedural.items import place_items
from homesim.world.procedural.parts import Part, box3
from homesim.world.procedural.plan import make_plan, room_kinds
from homesim.world.procedural.structure import build_shell, door_rects

ATTEMPTS = 5
"""Fresh draws (from the same seed's stream) before giving up on a home that fails the
checks (none has needed a second one on seeds 0-99)."""


def generate_home(seed: int, rooms: list[str] | None = None,
                  kb: ClassKnowledge | None = None) -> EnvironmentGraph:
    """A procedurally generated home; same seed and rooms -> the same graph (and bytes).

    `rooms` lists room kinds (`homesim.world.procedural.KINDS`); by default the four core
    kinds and up to four more. Raises `GraphError` if no valid home comes out."""
    kb = kb or default_kb()
    rng = random.Random(f"homesim-home-{seed}")
    kinds = room_kinds(rng, rooms)
    problem = ""
    for _ in range(ATTEMPTS):
        graph = _draw(rng, kinds, kb, seed)
        problems = check_home(graph)
        if not problems:
            return graph
        problem = problems[0]
    raise GraphError(f"seed {seed}: no valid home in {ATTEMPTS} attempts ({problem})")


def _draw(rng: random.Random, kinds: list[str], kb: ClassKnowledge, seed: int
          ) -> EnvironmentGraph:
    from homesim.world.procedural.build import to_graph

    plan = make_plan(rng, kinds)
    parts = build_shell(plan)
    for room in range(len(plan.rooms)):
        entries = furnish_room(rng, plan, parts, room)
        place_items(rng, parts, room, entries, kb)
    parts.append(_character(rng, plan, parts, kinds))
    meta = {"generator": {"seed": seed, "rooms": kinds, "by": "homesim.world.procedural"}}
    return to_graph(parts, meta)


def _character(rng: random.Random, plan, parts: list[Part], kinds: list[str]) -> Part:
    """The character, standing on free floor of the living room (or the first room)."""
    order = [r.kind for r in plan.rooms]
    room = order.index("living_room") if "living_room" in order else 0
    f = RoomFurnisher(rng, plan, parts, room)
    obstacles = [p.footprint for p in parts if p.room == room and p.kind == "fixture"
                 and blocks(p.box)]
    floor = FreeFloor(f.interior, obstacles)
    cells = sorted(floor.component(floor.cells_near(door_rects(plan, room)[0], DOOR_REACH)))
    i, j = rng.choice(cells)
    x, z = floor.x(i), floor.z(j)
    return Part("character", room, box3(x - 0.25, 0.0, z - 0.18, x + 0.25, 1.7, z + 0.18),
                kind="character")


def write_home(graph: EnvironmentGraph, path: str | Path) -> None:
    """Save a generated home (checked again: a home that fails is never written)."""
    problems = check_home(graph)
    if problems:
        raise GraphError(f"{path}: not written, the home fails its checks: {problems[0]}")
    graph.save(path)
