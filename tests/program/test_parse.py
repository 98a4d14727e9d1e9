import pytest

from homesim.errors import ArityError, ProgramError, UnknownActionError
from homesim.program import ObjectRef, Program, Step, parse_program, parse_step


@pytest.mark.parametrize(
    ("line", "canonical"),
    [
        ("[Walk] <television> (1)", "[Walk] <television> (1)"),
        ("[WALK] <television> (1)", "[Walk] <television> (1)"),
        ("  [walk]   <television>(1)  ", "[Walk] <television> (1)"),
        ("[SWITCHON] <computer> (1.417)", "[SwitchOn] <computer> (1.417)"),
        ("[PUTBACK] <cup> (1.1000) <table> ( 1.226 )", "[PutBack] <cup> (1.1000) <table> (1.226)"),
        ("[StandUp]", "[StandUp]"),
        ("[Walk] <Coffee Table> (2)", "[Walk] <coffee_table> (2)"),
        ("[Put] <cup> (1) <table> (1)", "[PutBack] <cup> (1) <table> (1)"),
    ],
)
def test_step_forms_print_canonically(line, canonical):
    step = parse_step(line)
    assert str(step) == canonical
    assert parse_step(str(step)) == step


def test_grounded_ref_keeps_instance_and_node():
    step = parse_step("[Grab] <mouse> (2.413)")
    assert step.obj == ObjectRef("mouse", 2, 413)
    assert step.obj.node == 413
    assert parse_step("[Grab] <mouse> (2)").obj.node == 2


def test_activity_file_format_round_trips():
    text = "Watch TV\nI sit and watch.\n\n\n[WALK] <tv> (1.410)\n\n[SWITCHON] <tv> (1.410)\n"
    p = parse_program(text)
    assert (p.title, p.description, len(p)) == ("Watch TV", "I sit and watch.", 2)
    assert str(p).startswith("Watch TV\nI sit and watch.\n\n[Walk] <tv> (1.410)")
    assert parse_program(str(p)) == p


def test_steps_only_text_has_no_title():
    p = parse_program("\n[Walk] <sofa> (1)\n# a comment\n[Sit] <sofa> (1)\n")
    assert p.title == "" and len(p) == 2
    assert parse_program(str(p)) == p


@pytest.mark.parametrize(
    ("text", "error", "pattern"),
    [
        ("[Wlak] <tv> (1)", UnknownActionError, r"line 1: '\[Wlak\] <tv> \(1\)': unknown action 'Wlak' \(did you mean Walk\?\)"),
        ("[Fly] <tv> (1)", UnknownActionError, r"unknown action 'Fly'$"),
        ("[Walk] <tv>", ProgramError, r"expected an id like '\(1\)' or '\(1.417\)' after <tv>"),
        ("[Walk] <tv> (one)", ProgramError, r"expected an id"),
        ("[Walk]", ArityError, r"\[Walk\] takes 1 object, got 0"),
        ("[PutBack] <cup> (1)", ArityError, r"\[PutBack\] takes 2 objects, got 1"),
        ("[StandUp] <sofa> (1)", ArityError, r"takes 0 objects, got 1"),
        ("[Walk] <> (1)", ProgramError, r"expected an object name"),
        ("[Walk] <tv> (1) now", ProgramError, r"expected an object like '<sofa> \(1\)' but found 'now'"),
        ("Walk <tv> (1)", ProgramError, r"expected a step like"),
    ],
)
def test_malformed_lines_name_line_text_and_expectation(text, error, pattern):
    with pytest.raises(error, match=pattern):
        parse_step(text, lineno=1)


def test_error_in_program_names_its_line_and_source():
    text = "Title\nDesc\n\n[Walk] <tv> (1)\nWalk to the sofa\n"
    with pytest.raises(ProgramError) as info:
        parse_program(text, source="p.txt")
    err = info.value
    assert (err.line, err.text, err.source) == (5, "Walk to the sofa", "p.txt")
    assert str(err).startswith("p.txt:line 5:")


def test_program_values_are_hashable_and_equal_by_content():
    a = Program.parse("[Walk] <sofa> (1)")
    b = Program((Step.parse("[WALK] <sofa> (1)"),))
    assert a == b and hash(a) == hash(b)


def test_program_rejects_multiline_description():
    with pytest.raises(ValueError, match="single line"):
        Program((), "t", "a\nb")


def test_object_refs_in_order_of_first_use():
    p = parse_program("[Walk] <cup> (1)\n[Grab] <cup> (1)\n[PutBack] <cup> (1) <table> (2)")
    assert [str(r) for r in p.object_refs()] == ["<cup> (1)", "<table> (2)"]
    assert not p.is_grounded
    assert parse_program("[Walk] <cup> (1.5)").is_grounded
