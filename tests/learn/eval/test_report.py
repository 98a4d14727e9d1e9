from homesim.learn.eval.report import REGENERATE, markdown_table

ROW = {"action": 0.5, "objects": 0.25, "steps": 0.125, "mean": 0.2917, "simulator": 42.0, "n": 3}


def test_markdown_has_one_table_per_data_set_and_the_command():
    results = [{"dataset": name, "n_test": 3, "n_train": 9, "rows": {"MLE": ROW},
                "train_seconds": {"mle": 12.0, "pg_lcs": None}} for name in ("real", "synthetic")]
    text = markdown_table(results, eval_seconds=5.0, machine="test box")
    assert text.count("| Method | Action | Objects | Steps | Mean | Simulator % |") == 2
    assert "| MLE | 0.500 | 0.250 | 0.125 | 0.292 | 42.0 |" in text
    assert "### Synthetic data (test n=3, train n=9)" in text
    assert REGENERATE in text and "test box" in text and "mle 12 s" in text
