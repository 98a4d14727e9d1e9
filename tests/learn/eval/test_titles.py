import json

import pytest

from homesim.errors import DataError
from homesim.learn.eval.titles import evaluate, prompts, read_predictions, title_splits


@pytest.fixture(scope="module")
def splits(real_data):
    return title_splits(0, real_data)


def test_prompts_are_titles_only(splits):
    p = prompts(splits)
    assert len(p) == len(splits.test) > 50
    assert all(x["prompt"].startswith("Task: ") and "." not in x["prompt"] for x in p)
    assert all(e.description == "" for e in splits.train)


def test_predictions_file_scores_against_the_test_programs(splits, tmp_path):
    first, second = splits.test[:2]
    path = tmp_path / "preds.json"
    path.write_text(json.dumps({first.id: str(first.program), second.id: "[Walk] <moon> (1)"}))
    preds = read_predictions(path, splits)
    assert preds[0].steps == first.program.steps and len(preds[2].steps) == 0
    scores = evaluate(preds, splits, runs=lambda p, e: p.steps == e.program.steps)
    assert scores.n == len(splits.test)
    assert scores.simulator == pytest.approx(100 / len(splits.test))
    assert 0 < scores.steps < 1


def test_bad_predictions_file(splits, tmp_path):
    path = tmp_path / "preds.json"
    path.write_text("[1, 2]")
    with pytest.raises(DataError, match="expected a JSON object"):
        read_predictions(path, splits)
