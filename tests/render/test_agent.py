import pytest

from homesim.errors import HomesimError
from homesim.render.agent import AGENTS, HINGES, agent_mjcf, agent_shape


def test_four_agents_differ_and_unknown_agent_is_an_error():
    assert len(AGENTS) == 4 and len({a.height for a in AGENTS.values()}) == 4
    with pytest.raises(HomesimError, match="unknown agent 'robot'"):
        agent_shape("robot")




def test_agent_mjcf_names_every_hinge_and_keypoint():
    xml = agent_mjcf(AGENTS["male1"])
    assert all(f'name="a:{h}"' in xml for h in HINGES)
    assert xml.count('<site name="j:') == 16
