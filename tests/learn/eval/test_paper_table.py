from homesim.learn.eval.paper_table import ROWS, RunConfig, evaluate_dataset, train_dataset
from homesim.learn.eval.report import markdown_table


def test_train_then_score_every_row(tmp_path):
    config = RunConfig("synthetic", seed=3, synth_n=30, mle_epochs=1, pg_epochs=1,
                       batch_size=8)
    stages = []
    paths = train_dataset(config, tmp_path, lambda s, d, t, v: stages.append(s))
    assert set(paths) == {"mle", "pg_lcs", "pg_lcs_sim"}
    assert {"MLE", "PG (LCS)", "PG (LCS+Sim)"} <= set(stages)
    result = evaluate_dataset(tmp_path)
    assert tuple(result["rows"]) == ROWS
    assert result["n_test"] == 6
    for row in ROWS:
        s = result["rows"][row]
        assert 0 <= s["steps"] <= 1 and 0 <= s["simulator"] <= 100 and s["n"] == 6
    assert result["rows"]["PG (LCS+Sim) + constrained decoding"]["simulator"] == 100.0
    text = markdown_table([result], eval_seconds=1.0)
    assert "| Method | Action | Objects | Steps | Mean | Simulator % |" in text
