import pytest

from homesim.errors import GoalError
from homesim.goals.formula import Atom, Nary, Quantified, parse_formula


@pytest.mark.parametrize("text", [
    "ON(tv.410)",
    "(ON(tv.410) and PLUGGED_IN(tv.410))",
    "(exists x0. (TYPE(x0)) then ON(computer.417))",
    "(exists x0. ((TOUCH(x0) or PUSH(x0))) then (ON(tv.1) and FACING(character.65, tv.1)))",
    "not ONTOP(cup.3, table.5)",
    "forall x. (not HOLDS_RH(character.1, x))",
    "forn 2. x. (GRAB(x))",
])
def test_print_parses_back_to_the_same_formula(text):
    f = parse_formula(text)
    assert parse_formula(str(f)) == f
    assert str(parse_formula(str(f))) == str(f)


def test_precedence_then_or_and():
    f = parse_formula("ON(a.1) then OFF(a.1) or CLOSED(b.2) and OPEN(c.3)")
    assert isinstance(f, Nary) and f.op == "then"
    right = f.parts[1]
    assert right.op == "or" and right.parts[1].op == "and"


def test_atom_kinds():
    f = parse_formula("exists x. (TYPE(x)) and ON(tv.1) and ONTOP(cup.3, table.5)")
    q, state, rel = f.parts
    assert isinstance(q, Quantified) and q.body.kind == "action"
    assert isinstance(state, Atom) and state.kind == "state" and state.args[0].node == 1
    assert rel.kind == "relation"


@pytest.mark.parametrize(("text", "message"), [
    ("", "empty formula"),
    ("ON(tv.1) and", "column 13: expected an atom"),
    ("FLY(tv.1)", "column 1: unknown predicate 'FLY'"),
    ("ONTOP(tv.1)", "ONTOP does not take 1 argument"),
    ("GRAB(cup.1, table.2)", "action GRAB takes 1 object"),
    ("exists x. (TYPE(y))", "variable 'y' is not bound"),
    ("ON(tv.1) ON(tv.2)", "column 10: unexpected 'ON' after a complete formula"),
    ("(ON(tv.1)", "expected ')'"),
    ("ON(tv.1) & OFF(tv.1)", "unexpected '&'"),
])
def test_malformed_formulas_say_where_and_why(text, message):
    with pytest.raises(GoalError, match=message.replace("(", r"\(").replace(")", r"\)")):
        parse_formula(text)


def test_every_eai_formula_parses_and_round_trips(real_data):
    from homesim.goals.eai import load_eai_goals

    goals = load_eai_goals(real_data)
    assert len(goals) == 342
    formulas = [g.formula for g in goals.values() if g.formula is not None]
    assert len(formulas) == 338
    assert all(parse_formula(str(f)) == f for f in formulas)
