"""Bindings: the one encoding of which node of a home each program object is.

A program names objects by class and per-program instance (``<tv> (1)``). Grounding binds
each to a node of a home; the binding is carried either in the refs (``<tv> (1.410)``)
or as a `Bindings` map beside an ungrounded program. Both say the same thing:
`Bindings.of` reads the map off a grounded program and `Bindings.apply` writes it back.

>>> from homesim.program import parse_program
>>> p = parse_program("[Walk] <tv> (1.410)\\n[SwitchOn] <tv> (1.410)")
>>> b = Bindings.of(p)
>>> dict(b)
{('tv', 1): 410}
>>> print(b.apply(parse_program("[Walk] <tv> (1)")))
[Walk] <tv> (1.410)
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Mapping
from typing import Any, TypeVar, overload

from homesim.errors import BindingError
from homesim.program.model import ObjectRef, Program, Step

Key = tuple[str, int]
"""A program object: (class name, instance)."""
_T = TypeVar("_T")


class Bindings(Mapping[Key, int]):
    """An immutable map from program objects (class name, instance) to node ids."""

    __slots__ = ("_nodes",)

    def __init__(self, nodes: Mapping[Key, int] | Iterable[tuple[Key, int]] = ()):
        self._nodes: dict[Key, int] = dict(nodes)

    @classmethod
    def of(cls, program: Program, given: Mapping[Key, int] | None = None) -> Bindings:
        """The bindings of `program`: `given` plus the node ids its refs carry.

        Raises:
            BindingError: a ref has no node id and `given` does not bind it, or one
                object is bound to two different nodes (naming the step, object, nodes).
        """
        nodes: dict[Key, int] = dict(given or {})
        for index, step in enumerate(program.steps):
            for ref in step.args:
                node = ref.node_id
                if node is None:
                    if ref.key not in nodes:
                        raise unbound_error(index, step, ref)
                    continue
                known = nodes.setdefault(ref.key, node)
                if known != node:
                    raise BindingError(
                        f"{_where(index, step)}: <{ref.name}> ({ref.instance}) is node {node} "
                        f"here but node {known} at an earlier step; one object is one node",
                        index + 1, f"<{ref.name}> ({ref.instance})", node)
        return cls(nodes)

    def apply(self, program: Program) -> Program:
        """`program` with every ref it binds carrying its node id (``<tv> (1.410)``)."""
        return program.with_steps([
            Step(s.action, tuple(r.ground(self._nodes.get(r.key, r.node_id)) for r in s.args))
            for s in program.steps])

    def to_list(self) -> list[dict[str, Any]]:
        """JSON view: ``[{"name": "tv", "instance": 1, "node_id": 410}, ...]``."""
        return [{"name": n, "instance": i, "node_id": v} for (n, i), v in self._nodes.items()]

    def __getitem__(self, key: Key) -> int:
        return self._nodes[key]

    # get and in go straight to the dict: the simulator asks once per object ref, and
    # Mapping's own versions raise and catch KeyError for every miss.
    @overload
    def get(self, key: Key, /) -> int | None: ...
    @overload
    def get(self, key: Key, default: int | _T, /) -> int | _T: ...
    def get(self, key: Key, default: object = None, /) -> object:
        return self._nodes.get(key, default)

    def __contains__(self, key: object) -> bool:
        return key in self._nodes

    def __iter__(self) -> Iterator[Key]:
        return iter(self._nodes)

    def __len__(self) -> int:
        return len(self._nodes)

    def __repr__(self) -> str:
        return f"Bindings({self._nodes!r})"


def _where(index: int, step: Step) -> str:
    return f"step {index + 1} {step}"


def unbound_error(index: int, step: Step, ref: ObjectRef) -> BindingError:
    """The error for a ref at step `index` (0-based) that names no node."""
    return BindingError(
        f"{_where(index, step)}: <{ref.name}> ({ref.instance}) names no node: ground the "
        f"program first (homesim.run_program), or execute with reference=True to read "
        f"({ref.instance}) as node {ref.instance} as the reference simulator does",
        index + 1, f"<{ref.name}> ({ref.instance})")
