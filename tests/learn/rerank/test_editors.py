"""Which editors the reranker keeps."""

import pytest

from homesim.learn.rerank.reranker import Reranker


@pytest.mark.parametrize("deletions_help", [True, False])
def test_the_deleter_is_kept_only_where_its_cross_fitted_deletions_raise_the_lcs(
        tiny_splits, monkeypatch, deletions_help):
    from homesim.learn.rerank import editors

    def cross_deleted(chosen, written, config):
        if deletions_help:  # the truth itself: nothing scores higher
            return [q.example.program for q, *_ in chosen]
        return [p.with_steps(p.steps[:1]) for p in written]

    monkeypatch.setattr(editors, "cross_deleted", cross_deleted)
    model = Reranker.fit(tiny_splits.train, "program")
    assert model.inserter is not None
    assert (model.deleter is not None) == deletions_help
    assert Reranker.fit(tiny_splits.train, "program", delete=False).deleter is None
