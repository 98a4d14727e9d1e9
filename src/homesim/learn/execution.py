"""Execute predicted (ungrounded) programs in an example's home, as every entry point does.

`executable` is the simulator reward and the Simulator % column: `homesim.run_program`
(prepare the home, ground the program, execute it) with ``repair=False``: a model is
judged on the program it wrote, not on what repair would insert. `StepRunner` serves constrained
decoding, which must decide step by step: it accepts a step when the program so far plus
that step passes `run_program`, so a decoded program is executable by the same rules
(preparation, grounding with the knowledge base's equivalent names) as the reward.
"""

from __future__ import annotations

from functools import lru_cache

from homesim.ground.pipeline import run_program, runs
from homesim.learn.data import Example
from homesim.learn.vocabularies import StepKey, key_step
from homesim.program.actions import ACTIONS
from homesim.program.bindings import Bindings
from homesim.program.model import ObjectRef, Program, Step
from homesim.program.parse import parse_program
from homesim.world.graph import EnvironmentGraph
from homesim.world.homes import load_home

SEED = 0
"""Seed of preparation and grounding for the reward, the table and decoding."""


class StepRunner:
    """A program growing one ungrounded step at a time in an example's home.

    A step is accepted when `run_program` runs the steps accepted so far plus it (checked
    with `homesim.ground.pipeline.runs`: preparation and grounding, whose search runs every
    step). Verdicts on candidate steps are kept until the program grows.
    """

    def __init__(self, example: Example):
        self.graph = example.graph()
        self.steps: tuple[Step, ...] = ()
        self._verdicts: dict[Step, bool] = {}

    @property
    def bound(self) -> Bindings:
        """Program objects -> nodes of the prepared home, as `run_program` binds them."""
        bindings = run_program(Program(self.steps), self.graph, seed=SEED,
                               repair=False).bindings
        return bindings if bindings is not None else Bindings()

    def _runs(self, step: Step) -> bool:
        ok = self._verdicts.get(step)
        if ok is None:
            ok = self._verdicts[step] = runs(Program((*self.steps, step)), self.graph, seed=SEED)
        return ok

    def try_refs(self, action: str, refs: tuple[tuple[str, int], ...]) -> bool:
        """Append the step if the program with it runs; else change nothing.

        `refs` are the step's objects as (class name, instance).
        """
        step = Step(ACTIONS[action], tuple(ObjectRef(*r) for r in refs))
        ok = self._runs(step)
        if ok:
            self.steps += (step,)
            self._verdicts = {}
        return ok

    def try_step(self, key: StepKey) -> bool:
        """`try_refs` for a vocabulary step."""
        return self.try_refs(key[0], key[1])

    def can_run(self, key: StepKey) -> bool:
        """Whether the step could be appended now (nothing changes)."""
        return self._runs(key_step(key))


def executable(program: Program, example: Example) -> bool:
    """Whether `run_program` runs `program` in the example's home."""
    return run_program(program, example.graph(), seed=SEED, repair=False).executable


def repaired(program: Program, example: Example) -> Program | None:
    """`program` with the steps repair inserts so that it runs in the example's home
    (`homesim.ground.repair`), or None when repair finds no fix."""
    return repaired_in(program, example.graph())


def repaired_in(program: Program, graph: EnvironmentGraph, seed: int = SEED
                ) -> Program | None:
    """`program` mended by repair to run in `graph`; itself when it runs as written; None
    when repair finds no fix."""
    run = run_program(program, graph, seed=seed, repair=True)
    return (run.repaired or program) if run.executable else None


BUILTIN_HOMES = tuple(f"scene{i}_trimmed" for i in range(1, 6))
"""The built-in homes predictions are also run in (cross-home Simulator %)."""
REAL_HOME = "scene1_trimmed"
"""The built-in home the real programs' stored graphs are versions of (apartment 1)."""


def other_homes(example: Example) -> tuple[str, ...]:
    """The built-in homes other than the example's own (real programs live in apartment 1)."""
    own = example.home or REAL_HOME
    return tuple(h for h in BUILTIN_HOMES if h != own)


@lru_cache(maxsize=200_000)
def runs_in_builtin(program_text: str, home: str) -> bool:
    """Whether `run_program` runs the program (its text) in a built-in home; cached, since
    retrieval rows propose the same training programs again and again."""
    return run_program(parse_program(program_text), load_home(home), seed=SEED,
                       repair=False).executable


def cross_home_rate(program: Program, example: Example) -> float:
    """Share of the other built-in homes (`other_homes`) in which the program runs."""
    homes = other_homes(example)
    text = str(program)
    return sum(runs_in_builtin(text, h) for h in homes) / len(homes)


def runs_greedily(program: Program, example: Example) -> bool:
    """Whether `StepRunner` accepts every step of `program` in turn."""
    runner = StepRunner(example)
    return all(runner.try_refs(s.action.key, tuple(r.key for r in s.args))
               for s in program.steps)
