"""Goal formulas: the temporal-logic goals of the Embodied Agent Interface (EAI).

Glossary:
    atom: ``ON(tv.410)`` (a node state), ``ONTOP(cup.3, table.5)`` (a relation),
        ``TYPE(x0)`` (an action on an object); arguments are ``class.id`` or variables.
    and / or / not: as usual; ``not`` binds tightest, then ``and``, ``or``, ``then``.
    then: ``A then B``: A is reached and B holds afterwards (see `homesim.goals.check`).
    exists / forall: ``exists x0. (TYPE(x0))`` over the objects of the home;
        ``forn N. x. (...)``: at least N objects.

Parse and print are inverses: ``str(parse_formula(t))`` is the canonical text.

>>> f = parse_formula("(exists x0. (TYPE(x0)) then ON(computer.417))")
>>> str(f)
'(exists x0. (TYPE(x0)) then ON(computer.417))'
>>> try:
...     parse_formula("ON(tv.1) and")
... except GoalError as e:
...     print(e)
formula column 13: expected an atom, '(', 'not' or a quantifier; found end of formula
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from homesim.errors import GoalError, LimitError
from homesim.limits import (
    MAX_FORMULA_ATOMS,
    MAX_FORMULA_CHARS,
    MAX_FORMULA_DEPTH,
    MAX_FORMULA_QUANTIFIERS,
    MAX_ID_DIGITS,
)
from homesim.program.actions import ACTIONS, lookup_action

# Predicates over node states (one argument) and relations (two), as EAI spells them.
STATE_PREDICATES = frozenset({
    "CLOSED", "OPEN", "ON", "OFF", "PLUGGED_IN", "PLUGGED_OUT", "SITTING", "LYING",
    "CLEAN", "DIRTY",
})
# EAI name -> environment-graph relation.
RELATION_PREDICATES = {
    "ONTOP": "ON", "ON": "ON", "INSIDE": "INSIDE", "NEXT_TO": "CLOSE", "CLOSE": "CLOSE",
    "FACING": "FACING", "HOLDS_RH": "HOLDS_RH", "HOLDS_LH": "HOLDS_LH", "BETWEEN": "BETWEEN",
}


@dataclass(frozen=True, slots=True)
class Arg:
    """An atom argument: a grounded object (``tv.410``) or a variable (``x0``)."""

    name: str
    node: int | None = None

    def __str__(self) -> str:
        return self.name if self.node is None else f"{self.name}.{self.node}"


@dataclass(frozen=True, slots=True)
class Atom:
    """``PRED(args)``; `kind` is ``state``, ``relation`` or ``action``."""

    predicate: str
    args: tuple[Arg, ...]
    kind: str

    def __str__(self) -> str:
        return f"{self.predicate}({', '.join(map(str, self.args))})"


@dataclass(frozen=True, slots=True)
class Not:
    """Negation."""

    body: Formula

    def __str__(self) -> str:
        return f"not {_wrap(self.body)}"


@dataclass(frozen=True, slots=True)
class Nary:
    """``and``, ``or`` or ``then`` over two or more parts."""

    op: str
    parts: tuple[Formula, ...]

    def __str__(self) -> str:
        return "(" + f" {self.op} ".join(_wrap(p, self.op) for p in self.parts) + ")"


@dataclass(frozen=True, slots=True)
class Quantified:
    """``exists x. (body)``, ``forall x. (body)`` or ``forn N. x. (body)``."""

    quantifier: str
    var: str
    body: Formula
    count: int = 1

    def __str__(self) -> str:
        head = f"forn {self.count}. {self.var}" if self.quantifier == "forn" else (
            f"{self.quantifier} {self.var}")
        return f"{head}. ({_strip(self.body)})"


Formula = Atom | Not | Nary | Quantified
_PRECEDENCE = {"then": 0, "or": 1, "and": 2}


def _strip(f: Formula) -> str:
    text = str(f)
    return text[1:-1] if isinstance(f, Nary) else text


def _wrap(f: Formula, op: str | None = None) -> str:
    # Nary always prints its own parentheses; others need none.
    return str(f)


_TOKEN = re.compile(r"\s*(?:(?P<num>\d+\b)|(?P<name>[A-Za-z_\-]\w*(?:\.\d+)?)|(?P<sym>[(),.]))")
_BLANK = re.compile(r"\s*\Z")
_KEYWORDS = {"and", "or", "then", "not", "exists", "forall", "forn"}


def parse_formula(text: str, strict_eai: bool = False) -> Formula:
    """Parse an EAI goal formula; `GoalError` names the column and what was expected.

    `strict_eai` also refuses what EAI's parser refuses: an ``and`` joining a state goal
    and a temporal one (a ``then`` inside; see `temporal`), e.g. ``ON(a.1) and (OFF(b.2)
    then ON(b.2))``; homesim judges those (all parts must hold on the segment).

    Limits (`homesim.limits`): `MAX_FORMULA_CHARS` characters (`LimitError`), nesting
    `MAX_FORMULA_DEPTH` levels deep, `MAX_FORMULA_ATOMS` atoms, `MAX_FORMULA_QUANTIFIERS`
    nested quantifiers, ids and ``forn`` counts of `MAX_ID_DIGITS` digits.
    """
    if not isinstance(text, str) or not text.strip():
        raise GoalError("formula: empty formula")
    if len(text) > MAX_FORMULA_CHARS:
        raise LimitError(f"formula: {len(text)} characters, over the limit of "
                         f"{MAX_FORMULA_CHARS} (MAX_FORMULA_CHARS)", "MAX_FORMULA_CHARS")
    formula = _Parser(text).parse()
    if strict_eai:
        temporal(formula, strict_eai=True)
    return formula


def temporal(formula: Formula, strict_eai: bool = False) -> bool:
    """Whether `formula` is a temporal goal in EAI's sense: it has a ``then`` (outside
    which ``not``, quantifiers and ``or`` pass it on). With `strict_eai`, an ``and`` of
    state and temporal parts is a `GoalError`, as EAI's ``SimpleTLAnd`` asserts."""
    if isinstance(formula, Atom):
        return False
    if isinstance(formula, Not | Quantified):
        return temporal(formula.body, strict_eai)
    kinds = [temporal(p, strict_eai) for p in formula.parts]
    if formula.op == "then":
        return True
    if strict_eai and formula.op == "and" and len(set(kinds)) > 1:
        raise GoalError(f"formula: {_clip(str(formula))} joins state and temporal goals with "
                        "'and', which EAI refuses (--strict-eai)")
    return any(kinds)


def _clip(text: str, most: int = 80) -> str:
    return text if len(text) <= most else text[:most] + "..."


class _Parser:
    """Recursive descent over the grammar ``then > or > and > not/atom`` (loosest first)."""

    def __init__(self, text: str):
        self.text = text
        self.tokens: list[tuple[str, str, int]] = []
        pos = 0
        while pos < len(text):
            if _BLANK.match(text, pos):  # only blanks left (matched in place: no copy)
                break
            m = _TOKEN.match(text, pos)
            if m is None:
                col = len(text) - len(text[pos:].lstrip()) + 1
                raise GoalError(f"formula column {col}: unexpected {text[col - 1]!r}", col)
            kind = m.lastgroup or "sym"
            self.tokens.append((kind, m.group(kind), m.start(kind) + 1))
            pos = m.end()
        self.i = 0
        self.bound: list[str] = []
        self.depth = 0
        self.atoms = 0

    def parse(self) -> Formula:
        f = self._binary(0)
        if self.i < len(self.tokens):
            _, value, col = self.tokens[self.i]
            raise GoalError(f"formula column {col}: unexpected {value!r} after a complete "
                            "formula (join parts with 'and', 'or' or 'then')", col)
        return f

    def _peek(self) -> str | None:
        return self.tokens[self.i][1] if self.i < len(self.tokens) else None

    def _col(self) -> int:
        return self.tokens[self.i][2] if self.i < len(self.tokens) else len(self.text) + 1

    def _expect(self, value: str, what: str) -> None:
        if self._peek() != value:
            found = self._peek()
            found = "end of formula" if found is None else repr(found)
            raise GoalError(f"formula column {self._col()}: expected {what}; found {found}",
                            self._col())
        self.i += 1

    def _binary(self, level: int) -> Formula:
        if level == 3:
            return self._unary()
        op = {0: "then", 1: "or", 2: "and"}[level]
        parts = [self._binary(level + 1)]
        while self._peek() == op:
            self.i += 1
            parts.append(self._binary(level + 1))
        return parts[0] if len(parts) == 1 else Nary(op, tuple(parts))

    def _unary(self) -> Formula:
        token = self._peek()
        if token not in ("not", "(", "exists", "forall", "forn"):
            return self._leaf(token)
        self._deeper()
        if token == "not":
            self.i += 1
            f: Formula = Not(self._unary())
        elif token == "(":
            self.i += 1
            f = self._binary(0)
            self._expect(")", "')'")
        else:
            f = self._quantified(token)
        self.depth -= 1
        return f

    def _deeper(self) -> None:
        """One level deeper; `GoalError` past `MAX_FORMULA_DEPTH`."""
        self.depth += 1
        if self.depth > MAX_FORMULA_DEPTH:
            raise GoalError(f"formula column {self._col()}: nested deeper than "
                            f"{MAX_FORMULA_DEPTH} levels (MAX_FORMULA_DEPTH)", self._col())

    def _leaf(self, token: str | None) -> Formula:
        if token is None or self.tokens[self.i][0] != "name" or token in _KEYWORDS:
            found = "end of formula" if token is None else repr(token)
            raise GoalError(f"formula column {self._col()}: expected an atom, '(', 'not' or "
                            f"a quantifier; found {found}", self._col())
        return self._atom()

    def _quantified(self, quantifier: str) -> Formula:
        self.i += 1
        count = 1
        if quantifier == "forn":
            if self.i >= len(self.tokens) or self.tokens[self.i][0] != "num":
                raise GoalError(f"formula column {self._col()}: expected a count after "
                                "'forn'", self._col())
            count = self._number(self.tokens[self.i][1], "the count of 'forn'")
            self.i += 1
            self._expect(".", "'.' after the count")
        var = self._peek()
        if var is None or self.tokens[self.i][0] != "name" or "." in var or var in _KEYWORDS:
            raise GoalError(f"formula column {self._col()}: expected a variable name after "
                            f"'{quantifier}'", self._col())
        self.i += 1
        self._expect(".", f"'.' after '{quantifier} {var}'")
        self._expect("(", "'(' around the quantified formula")
        if len(self.bound) == MAX_FORMULA_QUANTIFIERS:
            raise GoalError(f"formula column {self._col()}: more than "
                            f"{MAX_FORMULA_QUANTIFIERS} quantifiers nested "
                            "(MAX_FORMULA_QUANTIFIERS)", self._col())
        self.bound.append(var)
        body = self._binary(0)
        self.bound.pop()
        self._expect(")", "')'")
        return Quantified(quantifier, var, body, count)

    def _atom(self) -> Atom:
        name, col = self.tokens[self.i][1], self._col()
        self.atoms += 1
        if self.atoms > MAX_FORMULA_ATOMS:
            raise GoalError(f"formula column {col}: more than {MAX_FORMULA_ATOMS} atoms "
                            "(MAX_FORMULA_ATOMS)", col)
        self.i += 1
        self._expect("(", f"'(' after {name}")
        args: list[Arg] = []
        while self._peek() != ")":
            if args:
                self._expect(",", "',' or ')'")
            args.append(self._arg())
        self.i += 1
        return Atom(name, tuple(args), _kind(name, len(args), col))

    def _arg(self) -> Arg:
        token, col = self._peek(), self._col()
        if token is None or self.tokens[self.i][0] != "name":
            found = "end of formula" if token is None else repr(token)
            raise GoalError(f"formula column {col}: expected an object (class.id) or a "
                            f"variable; found {found}", col)
        self.i += 1
        if "." in token:
            cls, node = token.rsplit(".", 1)
            return Arg(cls, self._number(node, f"the id of {cls}", col))
        if token not in self.bound:
            raise GoalError(f"formula column {col}: variable {token!r} is not bound by "
                            "'exists' or 'forall' (objects are written class.id)", col)
        return Arg(token)


    def _number(self, digits: str, what: str, col: int | None = None) -> int:
        """An id or count; `GoalError` when it has more than `MAX_ID_DIGITS` digits."""
        if len(digits.lstrip("0")) > MAX_ID_DIGITS:
            col = self._col() if col is None else col
            raise GoalError(f"formula column {col}: {what} has {len(digits)} digits, over "
                            f"the limit of {MAX_ID_DIGITS} (MAX_ID_DIGITS)", col)
        return int(digits)


def _kind(name: str, arity: int, col: int) -> str:
    """Whether ``NAME/arity`` is a state, a relation or an action; `GoalError` if none."""
    if arity == 1 and name in STATE_PREDICATES:
        return "state"
    if arity == 2 and name in RELATION_PREDICATES:
        return "relation"
    action = lookup_action(name)
    if action is not None and name == name.upper():
        if action.arity != arity:
            raise GoalError(f"formula column {col}: action {name} takes {action.arity} "
                            f"object(s), not {arity}", col)
        return "action"
    known = sorted(STATE_PREDICATES | set(RELATION_PREDICATES) | set(ACTIONS))
    if name in known:
        raise GoalError(f"formula column {col}: {name} does not take {arity} argument(s)",
                        col)
    raise GoalError(f"formula column {col}: unknown predicate {name!r} (states: "
                    f"{', '.join(sorted(STATE_PREDICATES))}; relations: "
                    f"{', '.join(sorted(RELATION_PREDICATES))}; or an action name)", col)
