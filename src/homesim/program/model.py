"""Programs as values: `ObjectRef`, `Step` and `Program`.

Glossary:
    object ref: ``<cup> (1)``, a class name and a per-program instance number; steps that
        share a ref mean the same object. A grounded ref also carries the node id of the
        home's instance: ``<cup> (1.417)`` is instance 1, node 417.
    step: ``[PutBack] <cup> (1) <table> (1)``, an action and 0-2 object refs.
    program: a title, a one-line description and a list of steps (ActivityPrograms format).

All three are frozen and hashable; `str()` prints them canonically and parsing the printed
text gives an equal value back.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field, replace

from homesim.program.actions import ActionSpec
from homesim.program.syntax import read_step, read_text


@dataclass(frozen=True, slots=True)
class ObjectRef:
    """An object argument of a step: class name, instance number, optional node id.

    >>> str(ObjectRef("television", 1))
    '<television> (1)'
    >>> str(ObjectRef("television", 1, node_id=410))
    '<television> (1.410)'
    """

    name: str
    instance: int
    node_id: int | None = None
    node: int = field(init=False, repr=False, compare=False, hash=False)
    """The node id the ref names when no grounding is given: `node_id`, else `instance`
    (the reference simulator reads ``(417)`` as node 417)."""

    def __post_init__(self) -> None:
        # Cached because the simulator reads it on every step.
        object.__setattr__(self, "node", self.instance if self.node_id is None else self.node_id)

    def __str__(self) -> str:
        if self.node_id is None:
            return f"<{self.name}> ({self.instance})"
        return f"<{self.name}> ({self.instance}.{self.node_id})"

    @property
    def key(self) -> tuple[str, int]:
        """The identity of the object within its program: (class name, instance)."""
        return (self.name, self.instance)

    def ground(self, node_id: int | None) -> ObjectRef:
        """The same ref bound to a node of a home (or unbound with None)."""
        return replace(self, node_id=node_id)


@dataclass(frozen=True, slots=True)
class Step:
    """One step: an action and its object refs.

    >>> step = Step.parse("[WALK] <television> (1)")
    >>> str(step)
    '[Walk] <television> (1)'
    """

    action: ActionSpec
    args: tuple[ObjectRef, ...] = ()
    nodes: tuple[int, ...] = field(init=False, repr=False, compare=False, hash=False)
    """The node ids of the objects when no grounding is given (see `ObjectRef.node`)."""

    def __post_init__(self) -> None:
        if len(self.args) != self.action.arity:
            raise ValueError(
                f"[{self.action.name}] takes {self.action.arity} object(s), got {len(self.args)}"
            )
        # Cached because the simulator reads it on every step.
        object.__setattr__(self, "nodes", tuple(ref.node for ref in self.args))

    @classmethod
    def parse(cls, line: str, lineno: int = 1, source: str | None = None) -> Step:
        """Parse one step line; raises `ProgramError` (naming `lineno` and `source`) on a
        malformed line."""
        action, refs = read_step(line, lineno, source)
        return cls(action, tuple([ObjectRef(*ref) for ref in refs]))

    def __str__(self) -> str:
        return " ".join([f"[{self.action.name}]", *map(str, self.args)])

    @property
    def obj(self) -> ObjectRef | None:
        """The first object (what the action is done to), if any."""
        return self.args[0] if self.args else None

    @property
    def target(self) -> ObjectRef | None:
        """The second object (where something is put or poured), if any."""
        return self.args[1] if len(self.args) > 1 else None


@dataclass(frozen=True, slots=True)
class Program:
    """A program: steps plus an optional title and one-line description.

    >>> p = Program.parse("[Walk] <sofa> (1)\\n[Sit] <sofa> (1)")
    >>> len(p), str(p.steps[1])
    (2, '[Sit] <sofa> (1)')
    """

    steps: tuple[Step, ...] = ()
    title: str = ""
    description: str = field(default="")

    def __post_init__(self) -> None:
        if "\n" in self.title or "\n" in self.description:
            raise ValueError("title and description must each be a single line")
        if self.description and not self.title:
            raise ValueError("a program with a description needs a title")

    @classmethod
    def parse(cls, text: str, source: str | None = None) -> Program:
        """Parse a program text (steps only, or the ActivityPrograms file format)."""
        title, description, lines = read_text(text, source)
        return cls(tuple([Step.parse(line, n, source) for n, line in lines]), title, description)

    def __str__(self) -> str:
        body = "\n".join(str(s) for s in self.steps)
        if not self.title:
            return body
        return f"{self.title}\n{self.description}\n\n{body}"

    def __len__(self) -> int:
        return len(self.steps)

    def __iter__(self) -> Iterator[Step]:
        return iter(self.steps)

    def object_refs(self) -> list[ObjectRef]:
        """Every distinct object ref of the program, in order of first use."""
        seen: dict[tuple[str, int], ObjectRef] = {}
        for step in self.steps:
            for ref in step.args:
                seen.setdefault(ref.key, ref)
        return list(seen.values())

    @property
    def is_grounded(self) -> bool:
        """True when every object ref carries a node id."""
        return all(ref.node_id is not None for step in self.steps for ref in step.args)

    def with_steps(self, steps: tuple[Step, ...] | list[Step]) -> Program:
        """The same program (title, description) with other steps."""
        return replace(self, steps=tuple(steps))
