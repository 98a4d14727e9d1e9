"""Candidate edits of a retrieved program: the objects the text names swapped in, the steps
using objects it does not name dropped (`base.Query` adds both to its candidates).

A *substitution* replaces an object class the text does not name by one it names and the
program lacks, where every step using the old class accepts the new one (the action
catalog's property needs; rooms only for rooms). A *drop* leaves out the steps that use a
class the text does not name (rooms are kept).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

import numpy as np

from homesim.knowledge.objects import load_kb
from homesim.learn.rerank.lexicon import classes
from homesim.program.model import Program
from homesim.world.vocab import ROOM_NAMES


def substitutions(program: Program, named: frozenset[str], chain_length: int
                  ) -> list[Program]:
    """`program` with one unnamed class replaced by a named one it lacks (every such swap the
    actions allow), then with the first allowed swap repeated up to `chain_length` times."""
    singles = _swaps(program, named)
    chain, current = [], program
    for _ in range(chain_length):
        swaps = _swaps(current, named)
        if not swaps:
            break
        current = swaps[0]
        chain.append(current)
    return singles + chain[1:]


def drops(program: Program, named: frozenset[str], implicit_rate: Callable[[str], float],
          chain_implicit: float) -> list[Program]:
    """`program` without the steps that use one class the text does not name (rooms kept),
    for each such class, then without all of those whose `implicit_rate` is below
    `chain_implicit` at once; never an empty program."""
    unnamed = sorted(classes(program) - named - ROOM_NAMES)
    rare = frozenset(c for c in unnamed if implicit_rate(c) < chain_implicit)
    out = [_without(program, frozenset({c})) for c in unnamed]
    if len(rare) > 1:
        out.append(_without(program, rare))
    return [p for p in out if p.steps]


def _without(program: Program, gone: frozenset[str]) -> Program:
    return program.with_steps([s for s in program.steps
                               if not any(r.name in gone for r in s.args)])


def _swaps(program: Program, named: frozenset[str]) -> list[Program]:
    used = classes(program)
    return [rename(program, old, new) for old in sorted(used - named)
            for new in sorted(named - used) if allows(program, old, new)]


def allows(program: Program, old: str, new: str) -> bool:
    """Whether every step of `program` using class `old` accepts class `new` there (the
    action catalog's property needs; a room only for a room)."""
    if (old in ROOM_NAMES) != (new in ROOM_NAMES):
        return False
    props = load_kb().properties(new)
    for step in program.steps:
        for position, ref in enumerate(step.args):
            if ref.name == old and not all(props & need
                                           for need in step.action.needs_of(position)):
                return False
    return True


def rename(program: Program, old: str, new: str) -> Program:
    """`program` with every object of class `old` called `new` (instances kept)."""
    return program.with_steps([replace(s, args=tuple(
        replace(r, name=new) if r.name == old else r for r in s.args)) for s in program.steps])


def mention_order(objects: list[str], named: frozenset[str], text: str) -> float:
    """Share of pairs of named classes that the program first uses in the order the text
    first says them (the last word of the class name); 0.5 when fewer than two."""
    lower = text.lower()
    where = {c: lower.find(c.split("_")[-1]) for c in named}
    order = list(dict.fromkeys(o for o in objects if where.get(o, -1) >= 0))
    pairs = [where[a] < where[b] for i, a in enumerate(order) for b in order[i + 1:]]
    return float(np.mean(pairs)) if pairs else 0.5

