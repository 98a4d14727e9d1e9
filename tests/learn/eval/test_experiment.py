"""One evaluation run on tiny synthetic data: every row, seeded, cached, summarised."""

from homesim.cli.main import main
from homesim.learn.eval.experiment import TITLE_ROW, RunSpec, block, cached_run, run
from homesim.learn.eval.report import MODEL_ROW, evaluation_markdown


def _examples(result: dict) -> dict:
    return {row: r["examples"] for row, r in result["rows"].items()}


def test_same_seed_same_scores_and_the_cache_is_reused(tmp_path, monkeypatch):
    from homesim.learn.eval import experiment

    monkeypatch.setattr(experiment, "MLE_DATASETS", ("synthetic",))  # every row, tiny data
    monkeypatch.setattr(experiment, "RERANK_DATASETS", ("synthetic",))
    spec = RunSpec("synthetic", "stratified", 3, synth_n=40, mle_epochs=1, embeddings="none")
    a = run(spec, tmp_path / "a")
    b = run(spec, tmp_path / "b")
    assert _examples(a) == _examples(b)
    assert {"Title-medoid", "NN (description)", "Rule parser (upper bound)", MODEL_ROW,
            "MLE + constrained decoding"} <= set(a["rows"])
    assert all(e["simulator"] == 1.0 for e in a["rows"]["MLE + constrained decoding"]["examples"])
    assert all(e["solved"] == 0.0 for e in a["rows"]["Empty program"]["examples"])
    assert _examples(cached_run(spec, tmp_path / "a")) == _examples(a)
    assert TITLE_ROW in a["rows"]  # the reranker given the title as its only text
    summary = block([a], {MODEL_ROW: ("Title-medoid",), TITLE_ROW: ("Title-median",)})
    text = evaluation_markdown({"real": {"stratified": summary}}, "box", "v")
    assert "| Empty program | 1 | 0.000 ± 0.000 |" in text
    assert "Goal (steps LCS at least 0.05 above Title-medoid):" in text
    assert "### Real data, stratified split (development seeds 3)" in text
    title_part = text.split("Title only:", 1)[1]
    assert f"| {TITLE_ROW} | 1 |" in title_part and f"| {TITLE_ROW} | 1 |" not in text.split(
        "Title only:", 1)[0]
    assert f"{TITLE_ROW} minus each baseline" in title_part
    text = evaluation_markdown({"synthetic": {"stratified": summary}}, "box", "v", 12.0,
                               cache="/tmp/fresh")
    assert "### Synthetic data, template text, stratified split" in text
    assert "12 s (with whatever was cached under /tmp/fresh)" in text
    assert "Goal" not in text  # the goal is set on real data only


def test_paraphrased_text_gets_the_reranker_and_the_rule_parser_not_the_seq2seq(tmp_path):
    spec = RunSpec("synthetic-people", "stratified", 0, synth_n=40, embeddings="none")
    rows = run(spec, tmp_path)["rows"]
    assert {MODEL_ROW, "Rule parser (upper bound)", "Title-medoid"} <= set(rows)
    assert not any(name.startswith("MLE") for name in rows)
    assert not (tmp_path / "synthetic-people" / "stratified" / "seed0" / "mle.pt").exists()
    parsed = [e["steps"] for e in rows["Rule parser (upper bound)"]["examples"]]
    assert sum(parsed) / len(parsed) < 0.9  # paraphrases are not the parser's templates


def test_every_seed_embeds_the_whole_data_set(tmp_path, monkeypatch):
    """The sentence vectors (floats depend on the batch) are the same whatever the seed's
    split keeps and whatever ran before."""
    from homesim.learn.eval import experiment

    embedded: list[list[str]] = []
    monkeypatch.setattr(experiment, "preload_vectors",
                        lambda examples, cache: embedded.append(sorted(e.id for e in examples)))
    split = experiment.make_split

    def dropping_one(*args: object) -> experiment.Splits:  # as deduplication does
        splits = split(*args)  # type: ignore[arg-type]
        return experiment.Splits(splits.name, splits.train, splits.dev, splits.test[1:])

    monkeypatch.setattr(experiment, "make_split", dropping_one)
    for seed in (0, 1):
        run(RunSpec("synthetic", "stratified", seed, synth_n=30), tmp_path, with_model=False)
    everything = sorted(e.id for e in experiment.load_examples("synthetic", 30))
    assert embedded == [everything, everything]


def test_table_command_summarises_cached_runs(tmp_path, capsys):
    spec = RunSpec("synthetic", "stratified", 0, synth_n=30)
    run(spec, tmp_path, with_model=False)
    md = tmp_path / "results.md"
    args = ["learn", "table", "--out", str(tmp_path), "--data", "synthetic", "--seeds", "2",
            "--synth-n", "30", "--only-cached", "--markdown", str(md)]
    assert main(args) == 0
    text = md.read_text()
    assert "### Synthetic data, template text, stratified split" in text and "Seeds 0;" in text
    assert "| Rule parser (upper bound) | 1 | 1.000 ± 0.000 |" in text
    assert main(["learn", "rules", "--synth-n", "30"]) == 0
    assert "rule parser: steps LCS 1.000 on 30 programs" in capsys.readouterr().out


def test_real_runs_do_not_depend_on_the_synthetic_size():
    stored = RunSpec("real", "stratified", 0, synth_n=5000).to_dict()
    assert RunSpec("real", "stratified", 0, synth_n=2000).matches(stored)
    assert not RunSpec("real", "stratified", 1, synth_n=5000).matches(stored)
    synthetic = RunSpec("synthetic", "stratified", 0, synth_n=5000).to_dict()
    assert not RunSpec("synthetic", "stratified", 0, synth_n=2000).matches(synthetic)


def test_a_run_cached_with_an_older_split_definition_is_not_reused(tmp_path):
    import json

    from homesim.learn.eval.splits import SPLIT_VERSIONS

    for split in SPLIT_VERSIONS:
        spec = RunSpec("synthetic", split, 0, synth_n=40, embeddings="none")
        old = {k: v for k, v in spec.to_dict().items() if k != "split_version"}  # saved before
        folder = spec.folder(tmp_path)
        folder.mkdir(parents=True)
        (folder / "scores.json").write_text(json.dumps({"spec": old, "rows": {"Row": {}}}))
        assert (cached_run(spec, tmp_path) is None) == (SPLIT_VERSIONS[split] > 1)
        assert not spec.matches({**spec.to_dict(), "split_version": SPLIT_VERSIONS[split] + 1})


def test_locked_seeds_only_with_final_and_every_final_run_is_counted(tmp_path, capsys):
    import pytest

    from homesim.errors import HomesimError
    from homesim.learn.eval import ledger

    with pytest.raises(HomesimError, match="seed 100: seeds from 100 on are the locked test"):
        run(RunSpec("synthetic", "stratified", 100, synth_n=30), tmp_path, with_model=False)
    md = tmp_path / "results.md"
    base = ["learn", "table", "--out", str(tmp_path), "--data", "synthetic", "--seeds", "1",
            "--synth-n", "30", "--no-model", "--markdown", str(md), "--force"]
    assert main(base) == 0  # development seeds only: no locked part, no ledger
    text = md.read_text()
    assert "(development seeds 0)" in text and "locked test seeds are not shown" in text
    assert not (tmp_path / "synthetic" / "stratified" / "seed100").exists()
    assert not (tmp_path / ledger.LEDGER).exists()
    assert main([*base, "--final"]) == 0
    text = md.read_text()
    assert "(locked test seeds 100)" in text and "was run 1 time for" in text
    assert text.index("## Locked test seeds 100") < text.index("## Development seeds 0")
    assert main(base) == 0  # without --final the locked part is kept as it was
    assert "(locked test seeds 100)" in md.read_text() and "was run 1 time for" in md.read_text()
    (tmp_path / ledger.LEDGER).unlink()  # a lost ledger forgets no run the markdown lists
    assert main([*base, "--final", "--only-cached"]) == 0
    assert "was run 2 times for" in md.read_text()
    assert len(ledger.listed(md.read_text())) == 2
    before = (tmp_path / "synthetic" / "stratified" / "seed0" / "scores.json").read_bytes()
    assert main([*base, "--final", "--dev-cached", "--workers", "2"]) == 0
    text = md.read_text()
    assert "was run 3 times for" in text and "(--dev-cached)" in text
    assert "(locked test seeds 100)" in text and "(development seeds 0)" in text
    assert (tmp_path / "synthetic" / "stratified" / "seed0" / "scores.json").read_bytes() == before


def test_a_cached_row_of_another_model_version_is_scored_again(tmp_path, monkeypatch):
    from homesim.learn.eval import experiment

    spec = RunSpec("synthetic", "stratified", 0, synth_n=30)
    first = run(spec, tmp_path, with_model=False)["rows"]["Title-medoid"]
    assert first["version"] == 1
    calls = []
    monkeypatch.setattr(experiment, "ROW_VERSIONS", {"Title-medoid": 2})
    monkeypatch.setattr(experiment.baselines, "title_medoid",
                        lambda train, test: calls.append(1) or [e.program for e in test])
    again = run(spec, tmp_path, with_model=False)["rows"]
    assert calls == [1] and again["Title-medoid"]["version"] == 2
    assert again["NN (title)"] == run(spec, tmp_path, with_model=False)["rows"]["NN (title)"]


def test_without_mle_no_model_is_trained_and_its_scored_rows_are_kept(tmp_path, monkeypatch):
    from homesim.learn.eval import experiment

    monkeypatch.setattr(experiment, "MLE_DATASETS", ("synthetic",))
    spec = RunSpec("synthetic", "stratified", 0, synth_n=30, mle_epochs=1, embeddings="none")
    rows = run(spec, tmp_path, with_model=False, with_mle=False)["rows"]
    assert not any(name in rows for name in experiment.MLE_ROWS)
    assert not (spec.folder(tmp_path) / "mle.pt").exists()
    trained = run(spec, tmp_path, with_model=False)["rows"]  # no reranker: quick
    assert not any(name in trained for name in experiment.MLE_ROWS)  # with_model off
    trained = run(spec, tmp_path)["rows"]
    kept = run(spec, tmp_path, with_mle=False)["rows"]
    assert list(kept) == list(trained)  # the seq2seq rows kept, in the table's order
    assert kept["MLE (seq2seq)"] == trained["MLE (seq2seq)"]


def test_runs_scored_in_parallel_processes_score_the_same(tmp_path):
    import json

    def table(out, workers):
        args = ["learn", "table", "--out", str(out), "--data", "synthetic", "--seeds", "2",
                "--synth-n", "30", "--no-model", "--workers", str(workers)]
        assert main(args) == 0
        return [json.loads((out / "synthetic" / "stratified" / f"seed{k}" / "scores.json")
                           .read_text())["rows"] for k in (0, 1)]

    assert _examples({"rows": table(tmp_path / "a", 2)[1]}) == _examples(
        {"rows": table(tmp_path / "b", 1)[1]})
