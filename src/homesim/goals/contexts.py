"""What scoring a plan for one EAI-annotated program needs: `TaskContext`, and loading them.

A context holds the program's goals, its stored initial graph and its task objects (the
nodes whose state or edges differ between the stored initial and final graphs: EAI's list
of what a plan may name). The 342 initial graphs are read by
`homesim.knowledge.graphpairs.GraphPairReader`, which parses what they share once; the
whole set is also kept as a pickle beside the data, so a later process loads it without
reading the graphs.
"""

from __future__ import annotations

import hashlib
import pickle
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

from homesim.goals.eai import TaskGoals
from homesim.knowledge.graphpairs import changed_objects
from homesim.world.graph import EnvironmentGraph

task_objects = changed_objects
"""(class name, id) of the nodes whose dict or edges differ between two graph dicts."""


@dataclass(frozen=True)
class TaskContext:
    """What scoring a plan for one program needs.

    Attributes:
        goals: the program's goals.
        home: its initial graph.
        objects: (class name, node id) of the objects a plan may name.
    """

    goals: TaskGoals
    home: EnvironmentGraph
    objects: frozenset[tuple[str, int]]


SUBSET_BUILDS_ALL = 50
"""Without the cache, a request for more tasks than this builds (and caches) all of them."""


def load_contexts(ids: Iterable[str] | None = None, cache: bool = True
                  ) -> dict[str, TaskContext]:
    """`TaskContext` of every annotated program of the real data set (or of `ids`, EAI
    identifiers), keyed by EAI identifier.

    The full set is kept as a pickle beside the data (`_cache_path`), keyed by the data's
    manifest, the goal file and the source of the modules whose objects it holds: any
    change to them builds it again. A subset is taken from it when it is there; else a
    subset of up to `SUBSET_BUILDS_ALL` tasks is built alone, a larger one builds and
    caches the whole set. `cache` False neither reads nor writes it.
    """
    wanted = None if ids is None else {f"file{i}" for i in ids}
    path = _cache_path() if cache else None
    if wanted is not None and (path is None or not path.exists()) and (
            len(wanted) <= SUBSET_BUILDS_ALL):
        return _build_contexts(wanted)
    contexts = _read_cache(path) if path is not None else None
    if contexts is None:
        contexts = _build_contexts(None)
        if path is not None:
            _write_cache(path, contexts)
    if wanted is None:
        return contexts
    return {k: c for k, c in contexts.items() if f"file{k}" in wanted}


def _read_cache(path: Path) -> dict[str, TaskContext] | None:
    if not path.exists():
        return None
    try:
        with path.open("rb") as f:
            return pickle.load(f)  # our own file, written by _write_cache
    except Exception:
        return None


def _write_cache(path: Path, contexts: dict[str, TaskContext]) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(".tmp")
    with tmp.open("wb") as f:
        pickle.dump(contexts, f, protocol=pickle.HIGHEST_PROTOCOL)
    tmp.replace(path)


def _build_contexts(wanted: set[str] | None) -> dict[str, TaskContext]:
    from homesim.goals.eai import eai_id, load_eai_goals
    from homesim.knowledge.fetch import dataset_dir
    from homesim.knowledge.graphpairs import GraphPairReader

    goals = load_eai_goals()
    graphs = dataset_dir() / "graphs"  # the stored graphs of program fileN: fileN.json
    reader = GraphPairReader()
    out = {}
    for program in sorted(goals):
        if wanted is None or program in wanted:
            home, objects = reader.read(graphs / f"{program}.json")
            out[eai_id(program)] = TaskContext(goals[program], home, objects)
    return out


def _cache_path() -> Path | None:
    """``<data root>/eai-contexts/<key>.pickle``; None when the data is not fetched."""
    import homesim.goals.check
    import homesim.goals.eai
    import homesim.goals.formula
    import homesim.knowledge.graphpairs
    import homesim.program.model
    import homesim.world.graph
    import homesim.world.index
    from homesim.goals.eai import GOALS_FILE
    from homesim.knowledge.fetch import data_root, dataset_dir

    directory = dataset_dir()
    inputs = [directory / "MANIFEST.json", directory / GOALS_FILE, Path(__file__)]
    inputs += [Path(m.__file__) for m in (  # type: ignore[arg-type]
        homesim.goals.check, homesim.goals.eai, homesim.goals.formula,
        homesim.knowledge.graphpairs, homesim.program.model, homesim.world.graph,
        homesim.world.index)]
    digest = hashlib.sha256()
    for source in inputs:
        if not source.is_file():
            return None
        digest.update(source.read_bytes())
    return data_root() / "eai-contexts" / f"{digest.hexdigest()[:16]}.pickle"
