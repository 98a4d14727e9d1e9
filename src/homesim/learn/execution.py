"""Execute predicted (ungrounded) programs in an example's home.

`executable` grounds the whole program in the home with `homesim.ground` (backtracking
search over bindings) and executes it: this is the simulator reward and the Simulator %
column. `StepRunner` serves constrained decoding, which must decide step by step: it binds
each object the first time a step uses it (the node the true program used for it first,
then the other nodes of its class) and keeps the first that lets the step run. A program
it accepts is executable under that binding, so `ground` finds one too.
"""

from __future__ import annotations

from itertools import product

from homesim.errors import GroundingError
from homesim.ground.search import ground
from homesim.learn.data import Example
from homesim.learn.vocab import StepKey
from homesim.program.actions import ACTIONS
from homesim.program.model import ObjectRef, Program, Step
from homesim.sim.execute import execute, run_step
from homesim.sim.state import SimState

_MAX_CHOICES = 64  # cap on node combinations tried for one step


class StepRunner:
    """A simulated home that accepts or refuses one ungrounded step at a time."""

    def __init__(self, example: Example):
        self.graph = example.graph()
        self.state = SimState(self.graph)
        self.hints = example.bindings
        self.bound: dict[tuple[str, int], int] = {}

    def _candidates(self, ref: tuple[str, int]) -> list[int]:
        if ref in self.bound:
            return [self.bound[ref]]
        taken = set(self.bound.values())
        nodes = [n.id for n in self.graph.nodes_of_class(ref[0]) if n.id not in taken]
        hint = self.hints.get(ref)
        if hint in nodes:
            nodes = [hint, *[n for n in nodes if n != hint]]
        return nodes

    def try_refs(self, action: str, refs: tuple[tuple[str, int], ...]) -> bool:
        """Run the step if some binding lets it run (keeping its effects); else change nothing.

        `refs` are the step's objects as (class name, instance).
        """
        step = Step(ACTIONS[action], tuple(ObjectRef(*r) for r in refs))
        options = [self._candidates(r) for r in refs]
        for count, ids in enumerate(product(*options)):
            if count >= _MAX_CHOICES:
                break
            if len(set(ids)) < len(ids) and len(set(refs)) == len(refs):
                continue  # two different objects cannot be one node
            if run_step(self.state, step, ids) is None:
                for r, i in zip(refs, ids, strict=True):
                    self.bound.setdefault(r, i)
                return True
        return False

    def try_step(self, key: StepKey) -> bool:
        """`try_refs` for a vocabulary step (every object is instance 1)."""
        return self.try_refs(key[0], tuple((name, 1) for name in key[1]))

    def can_run(self, key: StepKey) -> bool:
        """Whether the step could run now (the state is left as it was)."""
        mark = self.state.mark()
        bound = dict(self.bound)
        ok = self.try_step(key)
        self.state.undo(mark)
        self.bound = bound
        return ok


def executable(program: Program, example: Example) -> bool:
    """Whether `program` can be grounded in the example's home and then executes."""
    graph = example.graph()
    try:
        grounding = ground(program, graph, seed=0)
    except GroundingError:
        return False
    return execute(program, graph, bindings=grounding.bindings).executable


def runs_greedily(program: Program, example: Example) -> bool:
    """Whether `StepRunner` accepts every step of `program` in turn."""
    runner = StepRunner(example)
    return all(runner.try_refs(s.action.key, tuple(r.key for r in s.args))
               for s in program.steps)
