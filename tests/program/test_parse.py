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


def test_id_over_the_digit_limit_is_a_program_error():
    # int() refuses strings over 4300 digits: this was a ValueError (issue 12)
    with pytest.raises(ProgramError, match=r"id of 4301 digits, over the limit of 9 "
                                           r"\(MAX_ID_DIGITS\)"):
        parse_program("[Walk] <tv> (" + "9" * 4301 + ")")
    with pytest.raises(ProgramError, match="MAX_ID_DIGITS"):
        parse_step("[Walk] <tv> (1." + "4" * 10 + ")")
    assert parse_step("[Walk] <tv> (1." + "4" * 9 + ")").obj.node_id == 444444444


def test_names_over_the_length_limit_are_program_errors():
    with pytest.raises(ProgramError, match=r"object name of 101 characters.*MAX_NAME_CHARS"):
        parse_step("[Walk] <" + "a" * 101 + "> (1)")
    with pytest.raises(UnknownActionError, match=r"action name of 5000 characters"):
        parse_step("[" + "w" * 5000 + "] <tv> (1)")


@pytest.mark.parametrize("line", [
    "[Walk] " + "<tv> (1) " * 25_000,  # the line of issue 12: every object echoed
    "[Walk] <tv> (1) " + "?" * 100_000,
    "[" + "x" * 100_000,
    "[" + "x" * 99 + "] <tv> (1)",
])
def test_errors_quote_a_bounded_excerpt_of_the_line(line):
    with pytest.raises(ProgramError) as info:
        parse_program(line, source="big.txt")
    message = str(info.value)
    assert len(message) < 400 and "\n" not in message and "…" in message
    assert message.startswith("big.txt:line 1: ")
    assert len(info.value.text) <= 81


def test_too_many_steps_or_bytes_is_a_limit_error():
    from homesim.errors import LimitError
    from homesim.limits import MAX_PROGRAM_BYTES, MAX_STEPS

    assert len(parse_program("[Walk] <tv> (1)\n" * MAX_STEPS).steps) == MAX_STEPS
    with pytest.raises(LimitError, match=r"more than 1000 steps.*\(MAX_STEPS\)") as info:
        parse_program("[Walk] <tv> (1)\n" * (MAX_STEPS + 1))
    assert info.value.limit == "MAX_STEPS"
    text = "Title\n" + "é" * (MAX_PROGRAM_BYTES // 2)  # under the limit in characters only
    with pytest.raises(LimitError, match=r"bytes, over the limit of 256 KiB") as info:
        parse_program(text)
    assert info.value.limit == "MAX_PROGRAM_BYTES"


def test_a_lone_surrogate_is_a_program_error():
    # JSON strings can carry one ("\ud800"); it cannot be encoded back to UTF-8
    with pytest.raises(ProgramError, match=r"line 2: .*not valid Unicode"):
        parse_program("[Walk] <tv> (1)\n[Walk] <tv\ud800> (1)")
