"""Routes that describe what programs can use: homes, the action catalog, a home's objects."""

from __future__ import annotations

from functools import lru_cache
from typing import Any

from fastapi import APIRouter, Request
from fastapi.responses import Response
from starlette.concurrency import run_in_threadpool

from homesim.errors import GraphError
from homesim.examples import DEMO_HOME
from homesim.program import ACTIONS, Category, actions_in
from homesim.serve.errors import ApiError, SafeJSONResponse
from homesim.serve.pool import answer_or_gone, settle_memory
from homesim.world.graph import EnvironmentGraph
from homesim.world.homes import home_names, is_generated, load_home

router = APIRouter(prefix="/api", tags=["catalog"])
LISTED_GENERATED = 3
"""Generated homes (seeds 0..n-1) offered in the editor's home list."""

CATEGORY_LABELS: dict[Category, str] = {
    Category.MOVEMENT: "Movement",
    Category.ATTENTION: "Attention",
    Category.HANDS: "Hands",
    Category.PLACING: "Placing",
    Category.OPEN_CLOSE: "Open / close",
    Category.DEVICES: "Devices",
    Category.BODY: "Body",
    Category.CLEANING: "Cleaning",
    Category.EATING: "Eating",
}
"""Palette names of the 9 editor categories, in toolbox order."""


def get_home(name: str) -> EnvironmentGraph:
    """A built-in home, or a 404 naming the homes there are. A built-in home loaded for
    the first time is set aside from the garbage collector's scans (`settle_memory`; not a
    generated one: any seed loads, and the cache lets old ones go)."""
    loaded = load_home.cache_info().misses
    try:
        home = load_home(name)
    except GraphError as e:
        raise ApiError(404, "home", str(e)) from None
    if load_home.cache_info().misses != loaded and not is_generated(name):
        settle_memory()
    return home


@router.get("/homes")
def list_homes() -> dict[str, Any]:
    """Built-in homes, then a few generated ones (``gen-SEED``; any seed loads);
    ``geometry`` is True for homes with boxes (renderable)."""
    homes = [{"name": n, "geometry": not n.endswith("_trimmed")} for n in home_names()]
    homes += [{"name": f"gen-{seed}", "geometry": True} for seed in range(LISTED_GENERATED)]
    return {"default": DEMO_HOME, "homes": homes}


@router.get("/actions")
def list_actions() -> dict[str, Any]:
    """The action catalog: every row (`ActionSpec.to_dict`, with ``connector`` and
    ``aliases``) in ``actions``, and the same rows by editor category."""
    categories = []
    for category, label in CATEGORY_LABELS.items():
        actions = [a.to_dict() for a in actions_in(category)]
        categories.append({"id": category.value, "label": label, "actions": actions})
    return {"count": len(ACTIONS), "actions": [a.to_dict() for a in ACTIONS.values()],
            "categories": categories}


@lru_cache(maxsize=16)
def _objects(name: str) -> dict[str, Any]:
    graph = get_home(name)
    rooms = {r.id: r.class_name for r in graph.rooms()}
    objects = []
    for node in graph:
        if node.id == graph.character_id:
            continue
        room = graph.room_of(node.id)
        objects.append({
            "id": node.id,
            "class_name": node.class_name,
            "category": node.category,
            "room_id": room,
            "room": rooms.get(room) if room is not None else None,
            "properties": sorted(node.properties),
            "states": sorted(node.states),
        })
    objects.sort(key=lambda o: (o["room"] or "~", o["class_name"], o["id"]))
    return {"home": name, "character": graph.character_id,
            "rooms": [{"id": i, "class_name": c} for i, c in sorted(rooms.items())],
            "objects": objects}


@router.get("/homes/{name}/objects")
async def list_objects(name: str, http: Request) -> Response:
    """Every object of a home (not the character) with its room, sorted by room and class;
    a generated home is made in a program worker (`homesim.serve.pool`)."""
    if is_generated(name):
        return await answer_or_gone(http.app.state.programs, _objects, name,
                                    http.is_disconnected)
    return SafeJSONResponse(await run_in_threadpool(_objects, name))
