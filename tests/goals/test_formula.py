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


# ------------------------------------------------------------------ limits (issue 40 D8)
def test_deep_nesting_is_a_one_line_error_not_a_recursion_error():
    for text in ("(" * 200 + "ON(tv.1)" + ")" * 200, "not " * 2000 + "ON(tv.1)",
                 "exists x. (" * 40 + "GRAB(x)" + ")" * 40):
        with pytest.raises(GoalError, match=r"nested deeper than 32 levels|more than 2 quant"):
            parse_formula(text)
    parse_formula("(" * 30 + "ON(tv.1)" + ")" * 30)  # within the limit


@pytest.mark.parametrize("text", ["ON(tv." + "9" * 4301 + ")", "forn " + "9" * 4301 +
                                  ". x. (GRAB(x))", "ON(tv.1234567890)"])
def test_long_ids_and_counts_are_refused_by_the_digit_limit(text):
    with pytest.raises(GoalError, match="digits, over the limit of 9"):
        parse_formula(text)


def test_a_formula_over_the_size_limit_is_refused_before_parsing():
    from homesim.errors import LimitError
    from homesim.limits import MAX_FORMULA_CHARS

    text = " and ".join(["ON(tv.1)"] * 100_000)  # about 1 MB
    with pytest.raises(LimitError, match="MAX_FORMULA_CHARS"):
        parse_formula(text)
    with pytest.raises(GoalError, match="more than 256 atoms"):
        parse_formula(" and ".join(["ON(tv.1)"] * 300))
    assert len(" " * (MAX_FORMULA_CHARS - 8) + "ON(tv.1)") == MAX_FORMULA_CHARS
    assert str(parse_formula(" " * (MAX_FORMULA_CHARS - 8) + "ON(tv.1)")) == "ON(tv.1)"


def test_tokenizing_is_linear_in_the_blanks():
    # The former tokenizer copied the rest of the text at every token (quadratic).
    text = "(" + " or ".join(["ON(tv.1)"] * 250) + ")" + " " * 10_000
    assert len(parse_formula(text).parts) == 250


def test_a_long_then_chain_is_checked_without_recursion(tiny_home):
    from homesim.goals.check import Trajectory, holds
    from homesim.program import parse_program
    from homesim.sim import execute

    run = execute(parse_program("[Walk] <tv> (14)\n[SwitchOn] <tv> (14)\n"
                                "[SwitchOff] <tv> (14)\n[SwitchOn] <tv> (14)"),
                  tiny_home, trace=True, reference=True)
    tr = Trajectory(tiny_home, run.trace)
    assert holds(parse_formula(" then ".join(["OFF(tv.14)", "ON(tv.14)"] * 2)), tr)
    assert not holds(parse_formula(" then ".join(["OFF(tv.14)", "ON(tv.14)"] * 3)), tr)
    assert holds(parse_formula(" then ".join(["ON(tv.14)"] * 200)), tr)
    assert not holds(parse_formula(" then ".join(["OFF(tv.14)"] * 200)), tr)


@pytest.mark.parametrize(("text", "refused"), [
    ("ON(a.1) and (OFF(b.2) then ON(b.2))", True),
    ("exists x. (GRAB(x)) and (OFF(b.2) then ON(b.2))", True),
    ("not ON(a.1) and forall x. (OFF(x) then ON(x))", True),
    ("(ON(a.1) then OFF(a.1)) and (OFF(b.2) then ON(b.2))", False),
    ("ON(a.1) or (OFF(b.2) then ON(b.2))", False),  # EAI allows it in 'or'
    ("ON(a.1) and OFF(b.2) then ON(b.2)", False),  # 'then' binds loosest
])
def test_strict_eai_refuses_and_of_state_and_temporal_goals(text, refused):
    from homesim.goals.formula import temporal

    f = parse_formula(text)  # homesim judges them all
    assert temporal(f) == ("then" in str(f))
    if refused:
        with pytest.raises(GoalError, match="joins state and temporal goals"):
            parse_formula(text, strict_eai=True)
    else:
        assert parse_formula(text, strict_eai=True) == f
