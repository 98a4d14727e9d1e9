"""The one error family of homesim.

Every error a user can cause (a bad program, a broken graph, a missing data set) is a
`HomesimError` whose message names where and why in one line. The CLI and the web API
catch `HomesimError` and print that line; any other exception is a bug of ours.
"""

from __future__ import annotations

from collections.abc import Mapping

from homesim.limits import EXCERPT_CHARS


def excerpt(text: str, limit: int = EXCERPT_CHARS) -> str:
    """`text` cut to `limit` characters with an ellipsis, for quoting user text in errors.

    >>> excerpt("x" * 100, 5)
    'xxxxx…'
    """
    return text if len(text) <= limit else text[:limit] + "…"


def one_line(text: str, limit: int = EXCERPT_CHARS) -> str:
    """`text` with its whitespace runs (line breaks too) folded to one space, cut as
    `excerpt` does: a message quoting another library's error stays one line.

    >>> one_line("a\\n  b", 3)
    'a b'
    """
    return excerpt(" ".join(text.split()), limit)


class HomesimError(Exception):
    """Base class of every error homesim raises on bad input."""


class ProgramError(HomesimError):
    """A program text that cannot be parsed.

    Attributes:
        line: 1-based line number in the text (0 when unknown).
        text: the offending line (at most `EXCERPT_CHARS` of it, see `excerpt`).
        expected: what a valid line would have had there.
        source: file name or other origin of the text, if known.
    """

    def __init__(self, line: int, text: str, expected: str, source: str | None = None):
        self.line = line
        self.text = excerpt(text.strip())
        self.expected = expected
        self.source = source
        where = f"{source}:" if source else ""
        super().__init__(f"{where}line {line}: {self.text!r}: {expected}")


class UnknownActionError(ProgramError):
    """A step names an action that is not in the catalog."""


class ArityError(ProgramError):
    """A step has the wrong number of arguments for its action."""


class LimitError(HomesimError):
    """An input over one of the limits in `homesim.limits` (size, steps, ...).

    Attributes:
        limit: the name of the limit in `homesim.limits` (``MAX_STEPS``).
    """

    def __init__(self, message: str, limit: str):
        self.limit = limit
        super().__init__(message)


class GraphError(HomesimError):
    """An environment graph that is malformed (dangling edge, duplicate id, bad types)."""


class ExecutionError(HomesimError):
    """A program cannot be executed on a graph at all (e.g. no character in the graph)."""


class BindingError(ExecutionError):
    """A program whose object refs name no node, or a node of another class.

    Attributes:
        step: 1-based number of the first step that uses the object.
        obj: the program object (``<tv> (1)``).
        node: the node id it names, if any.
    """

    def __init__(self, message: str, step: int, obj: str, node: int | None = None):
        self.step = step
        self.obj = obj
        self.node = node
        super().__init__(message)


class DataError(HomesimError):
    """A data set or resource that is missing, corrupt or of the wrong shape."""


class GroundingError(HomesimError):
    """A program that cannot be prepared or grounded in a home.

    Attributes:
        step: 1-based number of the step where the search failed (0 when no step applies).
        obj: the program object (``<cup> (1)``) that could not be placed or bound, if any.
        tried: what was tried, in words (classes, instances, destinations).
        kind: the `homesim.sim.FailureKind` of the precondition the search could not
            meet (``missing`` for an object the home lacks), when known.
    """

    def __init__(self, message: str, step: int = 0, obj: str | None = None, tried: str = "",
                 kind: str | None = None):
        self.step = step
        self.obj = obj
        self.tried = tried
        self.kind = kind
        self.bindings: Mapping[tuple[str, int], int] = {}
        """The search's choices when it failed, if any: a `homesim.program.Bindings` (named
        by its plain type here: this module sits below `homesim.program`)."""
        super().__init__(message)


class GoalError(HomesimError):
    """A goal or goal formula that is malformed (bad syntax, unknown predicate, arity).

    Attributes:
        column: 1-based column of the formula text where the problem is (0 when unknown).
    """

    def __init__(self, message: str, column: int = 0):
        self.column = column
        super().__init__(message)
