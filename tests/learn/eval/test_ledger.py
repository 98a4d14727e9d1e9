"""The record of final runs: written before scoring, read back from OUT and from markdown."""

import pytest

from homesim.errors import DataError
from homesim.learn.eval import ledger
from homesim.learn.eval.ledger import FinalRun


def test_a_run_round_trips_through_the_ledger_and_the_markdown(tmp_path):
    a = FinalRun("2025-01-02T03:04:05Z", "abc1234", ("real",), (100, 101, 102))
    b = FinalRun.now("def5678+dirty", ("real", "synthetic"), (100, 101))
    assert b.when.endswith("Z") and len(b.when) == 27  # to the microsecond
    assert ledger.read(tmp_path) == []
    ledger.record(tmp_path, a)
    ledger.record(tmp_path, b)
    assert ledger.read(tmp_path) == [a, b]
    text = "\n".join(["intro", *ledger.section([a, b]), "after"])
    assert "was run 2 times" in text and ledger.listed(text) == [a, b]
    assert "was run 1 time for" in "\n".join(ledger.section([a]))
    assert ledger.listed("no list here") == []
    assert ledger.merged([b, a], [a]) == [a, b]  # once each, oldest first


def test_the_start_is_read_from_the_clock_to_the_microsecond(monkeypatch):
    """Identity is (start, commit): at one-second resolution a quick second final run (as in
    test_experiment's, on a fast machine) merged into the first and was not counted."""
    from datetime import datetime, timezone

    clock = iter([datetime(2026, 1, 2, 3, 4, 5, 100, timezone.utc),
                  datetime(2026, 1, 2, 3, 4, 5, 90000, timezone.utc)])

    class Clock:
        @staticmethod
        def now(tz):
            return next(clock)

    monkeypatch.setattr(ledger, "datetime", Clock)
    first = FinalRun.now("abc1234", ("real",), (100,))
    second = FinalRun.now("abc1234", ("real",), (100,))
    listed = ledger.listed("\n".join(ledger.section([first])))
    assert ledger.merged(listed, [second]) == [first, second]


def test_two_runs_in_one_second_are_counted_twice():
    """Runs stamped to the second merged into one when started in the same second (the
    CLI test of the locked seeds failed on a fast machine: 'was run 2 times' read 1)."""
    first = FinalRun("2025-01-02T03:04:05.000001Z", "abc1234", ("real",), (100,))
    second = FinalRun("2025-01-02T03:04:05.500000Z", "abc1234", ("real",), (100,))
    assert ledger.merged([second], [first, second]) == [first, second]
    assert ".".join(FinalRun.now("abc1234", ("real",), (100,)).when.split(".")[1:]) != ""


def test_a_broken_ledger_is_one_line(tmp_path):
    (tmp_path / ledger.LEDGER).write_text('{"when": "x"}\n')
    with pytest.raises(DataError, match=r"final-runs.jsonl:1: not a final-run record"):
        ledger.read(tmp_path)
