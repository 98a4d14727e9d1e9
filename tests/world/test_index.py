"""The fixed index of a home, and sharing one home between threads."""

import gc
import sys
import threading
import weakref

import pytest

from homesim.errors import HomesimError
from homesim.ground import prepare_and_ground, unground
from homesim.sim import execute
from homesim.world import standing
from homesim.world.graph import EnvironmentGraph
from homesim.world.homes import load_builtin, load_home
from homesim.world.vocab import CLOSE


def test_index_is_built_with_the_graph(tiny_home):
    ix = tiny_home.index
    assert ix.character == 10 and ix.rooms == {1, 2}
    assert ix.by_class["cup"] == (12,)
    assert ix.close_symmetric == (ix.out[CLOSE] is ix.incoming[CLOSE])
    assert not hasattr(tiny_home, "_derived")


def test_final_graphs_keep_the_index_facts():
    home = load_home("scene1")
    assert home.index.close_symmetric and home.index.body_parts == frozenset()
    again = EnvironmentGraph.from_dict(home.to_dict())
    assert again.index.close_symmetric and again.index.out[CLOSE] is again.index.incoming[CLOSE]


def _run(home: EnvironmentGraph, program, seed: int) -> tuple:
    """Prepare, ground and execute; the answer as plain data to compare."""
    # TODO(pipeline): homesim.ground.pipeline.run_program once it lands.
    try:
        prepared, grounding = prepare_and_ground(program, home, seed=seed)
    except HomesimError as e:
        return ("failed", str(e))
    result = execute(grounding.program, prepared.graph)
    final = result.state.to_graph()
    return (str(grounding.program), grounding.standing, result.executable, result.reason,
            sorted(final.edges()), sorted((n.id, sorted(n.states)) for n in final))


@pytest.fixture(scope="module")
def programs(real_data):
    from homesim.knowledge.datasets import real_programs

    return [unground(rp.program) for rp in real_programs(real_data)[::60]]


def test_eight_threads_share_one_cached_home(programs):
    """Threads that prepare, ground and execute on one `load_home` home (and its shared
    floor plans, filled while they run) get exactly the single-thread answers."""
    fresh = load_builtin("scene1")  # a private copy, not the cached one
    jobs = [(p, seed) for p in programs for seed in (0, 1)]
    expected = [_run(fresh, p, seed) for p, seed in jobs]
    assert sum(e[0] != "failed" for e in expected) >= len(jobs) // 2
    load_home.cache_clear()  # a cold home: plans are built while the threads race
    home = load_home("scene1")
    results: dict[int, list] = {}
    barrier = threading.Barrier(8)

    def work(t: int) -> None:
        barrier.wait()
        order = jobs[t:] + jobs[:t]  # each thread starts elsewhere
        results[t] = [_run(home, p, seed) for p, seed in order]

    threads = [threading.Thread(target=work, args=(t,)) for t in range(8)]
    interval = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)  # switch threads often, so that races show
    try:
        for th in threads:
            th.start()
        for th in threads:
            th.join()
    finally:
        sys.setswitchinterval(interval)
    for t in range(8):
        assert results[t] == expected[t:] + expected[:t]


def test_floor_plans_go_away_with_their_homes():
    home = load_home("scene1")
    graphs = [EnvironmentGraph.from_dict(home.to_dict()) for _ in range(3)]
    for g in graphs:
        standing.FloorPlan.for_graph(g).spot_near(g.character_id)
        standing.note_prepared(EnvironmentGraph.from_dict(g.to_dict()), g, frozenset())
    refs = [weakref.ref(g) for g in graphs]
    keys = {id(g) for g in graphs}
    # Checked by key, not by count: other tests' homes may be freed meanwhile.
    assert keys <= set(standing._PLANS._entries)
    del graphs, g
    gc.collect()
    assert all(r() is None for r in refs)  # the cache kept none of them alive
    entries = standing._PLANS._entries
    assert all(entries.get(k) is None or entries[k][0]() is not None for k in keys)
