"""Description -> program examples: the real data set and the synthetic one, with splits.

Programs are kept ungrounded (``<cup> (1)``); each example remembers the home it belongs to
and how its objects were bound there, so predictions can be executed in that home.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import lru_cache
from pathlib import Path

from homesim.knowledge.datasets import ActivityDataset, ActivityProgram
from homesim.program.model import ObjectRef, Program, Step
from homesim.world.graph import EnvironmentGraph
from homesim.world.homes import load_home

SPLIT_FRACTIONS = (0.7, 0.1, 0.2)
"""Train, dev and test shares (stratified by activity, i.e. program title)."""


@dataclass(frozen=True)
class Example:
    """One description with its program and the home to execute predictions in.

    Attributes:
        id: real program id (``file1003_2``) or synthetic id (``synth-1-17``).
        text: what the model reads: title and description.
        program: the ungrounded program (its refs carry no node ids).
        activity: the title, used to stratify splits.
        home: built-in home name, or the path of a stored real graph file.
        bindings: (class name, instance) -> node id where the truth ran in that home.
    """

    id: str
    text: str
    program: Program
    activity: str
    home: str
    bindings: dict[tuple[str, int], int] = field(default_factory=dict, compare=False)

    def graph(self) -> EnvironmentGraph:
        """The home the program belongs to (loaded once per process)."""
        return _graph(self.home)


@dataclass(frozen=True)
class Splits:
    """Train, dev and test examples of one data set."""

    name: str
    train: list[Example]
    dev: list[Example]
    test: list[Example]


@lru_cache(maxsize=1024)
def _graph(home: str) -> EnvironmentGraph:
    if home.endswith(".json"):
        from homesim.knowledge.realdata import RealProgram

        init, _ = RealProgram("", Program(), Path(home)).graph_dicts()
        return EnvironmentGraph.from_dict(init, f"{home}:init_graph")
    return load_home(home)


def ungrounded(program: Program) -> tuple[Program, dict[tuple[str, int], int]]:
    """The program with node ids removed, and the bindings they gave."""
    bindings: dict[tuple[str, int], int] = {}
    steps = []
    for step in program.steps:
        for ref in step.args:
            if ref.node_id is not None:
                bindings.setdefault(ref.key, ref.node_id)
        steps.append(Step(step.action, tuple(ObjectRef(r.name, r.instance) for r in step.args)))
    return replace(program, steps=tuple(steps)), bindings


def _text(program: Program) -> str:
    return f"{program.title}. {program.description}".strip()


def real_examples(directory: Path | None = None) -> list[Example]:
    """The 518 real programs as examples (needs ``homesim data fetch``)."""
    from homesim.knowledge.realdata import real_programs

    out = []
    for rp in real_programs(directory):
        program, bindings = ungrounded(rp.program)
        out.append(Example(rp.id, _text(program), program, program.title.lower(),
                           str(rp.graph_path), bindings))
    return out


def synthetic_examples(n: int = 5000, seed: int = 0, path: Path | None = None) -> list[Example]:
    """Synthetic examples: read from a `homesim synth` file, or generated with `seed`."""
    from homesim.synth import generate, read_jsonl

    programs = read_jsonl(path) if path is not None else list(generate(n, seed))
    return [Example(sp.id, _text(sp.program), sp.program, sp.program.title.lower(), sp.home,
                    dict(sp.bindings)) for sp in programs]


def split(name: str, examples: list[Example], seed: int) -> Splits:
    """70/10/20 train/dev/test, stratified by activity; the same seed gives the same split.

    The split is `ActivityDataset.split` (activity = normalized title).
    """
    by_id = {e.id: e for e in examples}
    dataset = ActivityDataset([ActivityProgram(e.id, e.program) for e in examples], name)
    parts = dataset.split(seed, SPLIT_FRACTIONS)
    train, dev, test = ([by_id[item.id] for item in parts[k]] for k in ("train", "val", "test"))
    return Splits(name, train, dev, test)
