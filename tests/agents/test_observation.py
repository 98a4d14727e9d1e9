"""The observation shows the room, what is held and what is visible, with states."""

from __future__ import annotations

from homesim.agents.observation import observe, visible
from homesim.program import Step
from homesim.sim import SimState, run_step


def test_what_is_in_a_closed_container_is_not_visible(tiny_home):
    st = SimState(tiny_home)
    assert 12 not in visible(st)  # the cup in the closed fridge
    assert {11, 13, 16} <= set(visible(st)) and 14 not in visible(st)  # tv: other room
    run_step(st, Step.parse("[Walk] <fridge> (11)"), (11,))
    run_step(st, Step.parse("[Open] <fridge> (11)"), (11,))
    assert 12 in visible(st)


def test_text_and_structure_agree(tiny_home):
    st = SimState(tiny_home)
    for text in ("[Walk] <plate> (16)", "[Grab] <plate> (16)"):
        step = Step.parse(text)
        assert run_step(st, step, step.nodes) is None
    obs = observe(st, "plate 16 ON sofa 15")
    assert obs["holding"] == ("<plate> (16)",)
    assert obs["text"].splitlines()[0] == "You are in <kitchen> (1). You hold <plate> (16)."
    assert "You see: <fridge> (11) [CLOSED], <table> (13) [close], <plate> (16) [close]." \
        in obs["text"]
    assert obs["rooms"] == ("<kitchen> (1)", "<living_room> (2)")
    assert obs["text"].endswith("Goal: plate 16 ON sofa 15.")
    fridge = next(o for o in obs["objects"] if o["id"] == 11)
    assert fridge == {"id": 11, "name": "fridge", "states": "CLOSED", "close": 0}
