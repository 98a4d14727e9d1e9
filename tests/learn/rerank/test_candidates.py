"""Candidate edits: substitutions the actions allow, drops, mention order."""

from homesim.learn.rerank.candidates import allows, drops, mention_order, rename, substitutions
from homesim.learn.rerank.config import RerankConfig
from homesim.program.model import Program
from tests.learn.rerank.test_reranker import TV

CHAIN = RerankConfig().max_substitutions
IMPLICIT = RerankConfig().chain_implicit


def test_substitution_respects_the_actions_needs():
    program = Program.parse(TV)
    assert allows(program, "television", "light")  # both have a switch
    assert not allows(program, "television", "floor")  # a floor cannot be switched on
    assert not allows(program, "home_office", "light")  # rooms only for rooms
    assert str(rename(program, "television", "light")).count("<light> (1)") == 2
    swapped = substitutions(program, frozenset({"light", "bedroom"}), CHAIN)
    texts = {str(p) for p in swapped}
    assert str(rename(program, "television", "light")) in texts
    assert str(rename(rename(program, "home_office", "bedroom"), "television", "light")) in texts
    assert substitutions(program, frozenset({"television", "home_office"}), CHAIN) == []
    assert substitutions(program, frozenset({"light", "bedroom"}), 0) == swapped[:2]  # singles


def test_mention_order_compares_with_the_text():
    named = frozenset({"cup", "table"})
    assert mention_order(["cup", "table"], named, "take the cup to the table") == 1.0
    assert mention_order(["table", "cup"], named, "take the cup to the table") == 0.0
    assert mention_order(["cup"], named, "the cup") == 0.5


def test_drops_leave_out_unnamed_objects_but_never_rooms_or_everything():
    program = Program.parse(TV + "\n[Walk] <couch> (1)\n[Sit] <couch> (1)")
    rate = {"couch": 0.1, "television": 0.2}.get
    out = {str(p) for p in drops(program, frozenset(), lambda c: rate(c, 0.9), IMPLICIT)}
    assert str(Program.parse(TV)) in out  # couch left out
    assert str(Program.parse("[Walk] <home_office> (1)")) in out  # both rarely implicit
    assert all("home_office" in p for p in out)
    assert drops(Program.parse("[Walk] <couch> (1)"), frozenset(), lambda c: 0.1, IMPLICIT) == []
    assert len(drops(program, frozenset(), lambda c: rate(c, 0.9), 0.05)) == 2  # none rare
