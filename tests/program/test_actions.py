from homesim.program import ACTIONS, ANIMATED, Category, actions_in, lookup_action
from homesim.program.actions import suggest_action
from homesim.sim import EFFECTS

REFERENCE_ACTIONS = [
    "WALK", "RUN", "FIND", "GRAB", "OPEN", "CLOSE", "PUTBACK", "PUTIN", "PUTOBJBACK",
    "SWITCHON", "SWITCHOFF", "DRINK", "LOOKAT", "TURNTO", "WIPE", "PUTON", "PUTOFF", "GREET",
    "DROP", "READ", "POINTAT", "TOUCH", "LIE", "SLEEP", "WAKEUP", "SIT", "STANDUP", "TYPE",
    "PUSH", "PULL", "MOVE", "WASH", "RINSE", "SCRUB", "SQUEEZE", "PLUGIN", "PLUGOUT", "CUT",
    "EAT", "RELEASE", "WATCH", "POUR",
]


def test_catalog_holds_the_42_reference_actions():
    assert sorted(ACTIONS) == sorted(REFERENCE_ACTIONS)
    assert len(ACTIONS) == 42


def test_every_action_has_an_effect():
    assert set(EFFECTS) == set(ACTIONS)


def test_arity():
    assert {k for k, a in ACTIONS.items() if a.arity == 0} == {"STANDUP", "SLEEP", "WAKEUP"}
    assert {k for k, a in ACTIONS.items() if a.arity == 2} == {"PUTBACK", "PUTIN", "POUR"}


def test_nine_categories_cover_all_actions():
    assert len(Category) == 9
    assert sum(len(actions_in(c)) for c in Category) == 42
    assert all(actions_in(c) for c in Category)


def test_the_twelve_animated_actions():
    assert sorted(ANIMATED) == sorted(
        ["WALK", "RUN", "GRAB", "SWITCHON", "SWITCHOFF", "OPEN", "CLOSE", "PUTBACK", "LOOKAT",
         "SIT", "STANDUP", "TOUCH"]
    )


def test_lookup_any_case_and_suggestions():
    assert lookup_action("switchon").name == "SwitchOn"
    assert lookup_action("Switch On").key == "SWITCHON"
    assert lookup_action("teleport") is None
    assert suggest_action("SWICHON") == "SwitchOn"
    assert suggest_action("zzzz") is None


def test_two_object_actions_have_a_connector_and_aliases_name_their_action():
    assert {k for k, a in ACTIONS.items() if a.connector} == {"PUTBACK", "PUTIN", "POUR"}
    assert lookup_action("put").key == "PUTBACK" and lookup_action("LookAt_Short").key == "LOOKAT"
    assert all(len(a.needs) <= a.arity for a in ACTIONS.values())
