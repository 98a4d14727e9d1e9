import pytest

from homesim.errors import BindingError
from homesim.program import Bindings, parse_program


def test_of_and_apply_are_inverses():
    grounded = parse_program("[Walk] <tv> (1.410)\n[PutBack] <cup> (2.7) <tv> (1.410)")
    b = Bindings.of(grounded)
    assert b == {("tv", 1): 410, ("cup", 2): 7} and len(b) == 2
    ungrounded = parse_program("[Walk] <tv> (1)\n[PutBack] <cup> (2) <tv> (1)")
    assert b.apply(ungrounded) == grounded
    assert Bindings.of(ungrounded, given=b) == b
    assert b.to_list()[0] == {"name": "tv", "instance": 1, "node_id": 410}


def test_bindings_are_immutable():
    b = Bindings({("tv", 1): 410})
    with pytest.raises(TypeError):
        b[("tv", 1)] = 3  # type: ignore[index]


def test_an_unbound_ref_or_two_nodes_for_one_object_is_an_error():
    with pytest.raises(BindingError, match=r"^step 2 \[Sit\] <sofa> \(1\): <sofa> \(1\) names no"
                       r" node") as e:
        Bindings.of(parse_program("[Walk] <tv> (1.410)\n[Sit] <sofa> (1)"))
    assert (e.value.step, e.value.obj, e.value.node) == (2, "<sofa> (1)", None)
    with pytest.raises(BindingError, match="is node 9 here but node 410 at an earlier step"):
        Bindings.of(parse_program("[Walk] <tv> (1.410)\n[Walk] <tv> (1.9)"))
