import numpy as np
import pytest

from homesim.errors import HomesimError, LimitError
from homesim.learn import embeddings
from homesim.learn.data import real_examples
from homesim.learn.rerank.insertion import clauses
from homesim.learn.rerank.program_writer import ProgramWriter, check_text, load_writer, model_path
from homesim.limits import MAX_DESCRIPTION_CHARS
from homesim.world.homes import load_home
from tests.conftest import WRITER_ACTIVITIES

TV = "Turn on the TV and watch it from the sofa."


def _keys(program) -> list[str]:
    return [s.action.key.lower() for s in program.steps]


def test_writes_a_program_for_the_description_that_runs(small_writer):
    written = small_writer.write(TV, load_home("scene1"), title="Watch TV")
    assert written.program.title == "Watch TV" and written.program.description == TV
    assert "watch" in _keys(written.program)
    assert "television" in {ref.name for s in written.program.steps for ref in s.args}
    assert written.title_given and written.run.executable
    assert all(ref.node_id is None for s in written.program.steps for ref in s.args)
    data = written.to_dict()
    assert data["program"] == str(written.program) and data["executable"] is True
    assert data["run"]["steps"][0]["line"] == 4  # title, description, blank line, steps


def test_guesses_the_activity_when_no_title_is_given(small_writer):
    home = load_home("scene1")
    assert small_writer.write(TV, home).program.title == "Watch TV"
    lamp = small_writer.write("Switch on the lamp in the bedroom, it is dark.", home, title=" ")
    assert lamp.program.title == "Turn on light" and not lamp.title_given
    assert "switchon" in _keys(lamp.program)


def test_answer_does_not_depend_on_what_was_embedded_before(small_writer, monkeypatch):
    home = load_home("scene1")
    before = str(small_writer.write(TV, home, title="Watch TV").program)
    rng = np.random.default_rng(0)
    noise = {t: v / np.linalg.norm(v) for t, v in
             ((t, rng.normal(size=embeddings.WORD_DIM))
              for t in (TV, "Watch TV", *clauses(f"Watch TV. {TV}"), "watch television",
                        "switch on television", "walk television"))}
    monkeypatch.setattr(embeddings, "_VECTORS", {**embeddings._VECTORS, **noise})
    assert str(small_writer.write(TV, home, title="Watch TV").program) == before


def test_a_stored_writer_is_read_back_and_answers_the_same(real_data, tmp_path, monkeypatch):
    examples = [e for e in real_examples(real_data) if e.title in WRITER_ACTIVITIES[:2]]
    first = load_writer(examples, root=tmp_path)
    stored = list((tmp_path / "models").glob("writer-*.pkl"))
    assert stored == [model_path(first.key, tmp_path)]

    def no_fit(_examples):
        raise AssertionError("fitted again instead of read back")

    monkeypatch.setattr(ProgramWriter, "fit", classmethod(lambda cls, ex: no_fit(ex)))
    again = load_writer(examples, root=tmp_path)
    home = load_home("scene2")
    assert str(again.write(TV, home).program) == str(first.write(TV, home).program)


def test_an_unreadable_store_is_fitted_again(real_data, tmp_path):
    examples = [e for e in real_examples(real_data) if e.title == "Turn on light"]
    key = ProgramWriter.fit(examples).key
    path = model_path(key, tmp_path)
    path.parent.mkdir(parents=True)
    path.write_bytes(b"not a pickle")
    assert load_writer(examples, root=tmp_path).key == key
    assert path.read_bytes()[:1] == b"\x80"  # replaced by the fitted writer


def test_bad_text_is_one_clear_error():
    assert check_text("description", "  turn on\n the tv ") == "turn on the tv"
    with pytest.raises(HomesimError, match="description: empty"):
        check_text("description", " \n ")
    with pytest.raises(LimitError, match="MAX_DESCRIPTION_CHARS") as info:
        check_text("title", "x" * (MAX_DESCRIPTION_CHARS + 1))
    assert info.value.limit == "MAX_DESCRIPTION_CHARS"
