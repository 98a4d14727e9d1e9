from homesim.learn.eval.rules import parse
from homesim.program.metrics import lcs_steps


def test_the_rule_parser_inverts_todays_synthetic_text(tiny_splits):
    examples = [*tiny_splits.train, *tiny_splits.test]
    assert all(lcs_steps(parse(e.description), e.program) == 1.0 for e in examples)


def test_the_more_specific_phrase_wins_and_unknown_text_gives_nothing():
    p = parse("Take the hanger from the dresser, then sit on the chair.")
    assert [s.action.key for s in p.steps] == ["WALK", "OPEN", "GRAB", "WALK", "SIT"]
    assert [r.name for s in p.steps for r in s.args][:2] == ["hanger", "dresser"]
    assert len(parse("Make a cup of tea for grandma.")) == 0


def test_known_pieces_of_unknown_text_still_parse():
    p = parse("I am bored. Grab the cup, then I dance a little.")
    assert [s.action.key for s in p.steps] == ["WALK", "GRAB"]
