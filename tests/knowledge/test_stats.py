import math

import pytest

pytest.importorskip("numpy")
pytest.importorskip("scipy")

from homesim.knowledge.datasets import ActivityDataset
from homesim.knowledge.stats import (
    action_counts,
    activity_lcs,
    compute_stats,
    count_sentences,
    count_words,
    object_counts,
    pairwise_lcs,
    similarity_matrix,
    summarize,
)

TINY = {
    "a1": "Watch TV\nI go to the sofa. I watch TV.\n\n"
          "[Walk] <tv> (1)\n[SwitchOn] <tv> (1)\n[Sit] <sofa> (1)\n[Watch] <tv> (1)\n",
    "a2": "watch  tv.\nWatch the television\n\n[Walk] <tv> (1)\n[Sit] <sofa> (1)\n[Watch] <tv> (1)\n",
    "b1": "Read book\nRead a book!\n\n[Walk] <book> (1)\n[Grab] <book> (1)\n[Read] <book> (1)\n",
}


@pytest.fixture
def tiny():
    return ActivityDataset.from_texts(TINY, "tiny")


@pytest.mark.parametrize(("text", "sentences", "words"), [
    ("I go to the sofa. I watch TV.", 2, 8),
    ("Watch the television", 1, 3),
    ("Wait... what?! Yes.", 3, 3),
    ("I don't know, it's 5 o'clock", 1, 6),
    ("", 0, 0),
    ("...", 0, 0),
])
def test_sentences_and_words(text, sentences, words):
    assert count_sentences(text) == sentences
    assert count_words(text) == words


def test_table_1a(tiny):
    s = summarize(tiny)
    assert (s.programs, s.activities) == (3, 2)
    assert s.avg_steps == pytest.approx(10 / 3)
    assert s.avg_sentences == pytest.approx(4 / 3)
    assert s.avg_words == pytest.approx(14 / 3)


def test_pairwise_lcs(tiny):
    lengths, normalized = pairwise_lcs(tiny)
    # a1 vs a2: Walk tv, Sit sofa, Watch tv -> 3 of 4; nothing shared with b1
    assert lengths.tolist() == [[4, 3, 0], [3, 3, 0], [0, 0, 3]]
    assert normalized[0, 1] == normalized[1, 0] == pytest.approx(0.75)
    assert normalized[0, 2] == 0.0 and normalized[2, 2] == 1.0


def test_table_1b(tiny):
    lengths, normalized = pairwise_lcs(tiny)
    rows = activity_lcs(tiny, lengths, normalized)  # titles normalized: a1 and a2 group
    assert [(r.activity, r.programs, r.pairs) for r in rows] == [("watch tv", 2, 1)]
    assert rows[0].mean_lcs == 3 and rows[0].mean_normalized_lcs == pytest.approx(0.75)
    chosen = activity_lcs(tiny, lengths, normalized, activities=["Read Book", "Cook"])
    assert [(r.activity, r.programs, r.pairs) for r in chosen] == [("read book", 1, 0),
                                                                    ("cook", 0, 0)]
    assert math.isnan(chosen[0].mean_lcs)


def test_table_1c(tiny):
    _, normalized = pairwise_lcs(tiny)
    matrix = similarity_matrix(tiny, normalized)
    assert matrix.activities == ["read book", "watch tv"] and matrix.programs == [1, 2]
    assert math.isnan(matrix.values[0, 0])  # one program: no pairs
    assert matrix.values[0, 1] == matrix.values[1, 0] == 0.0
    assert matrix.values[1, 1] == pytest.approx(0.75)


def test_block_sorting_puts_similar_activities_together():
    kitchen = "[Walk] <kitchen> (1)\n[Open] <fridge> (1)\n[Grab] <milk> (1)\n[Close] <fridge> (1)\n"
    sofa = "[Walk] <couch> (1)\n[Sit] <couch> (1)\n[Watch] <television> (1)\n"
    texts = {"1": f"Alpha\nd\n\n{kitchen}", "2": f"Gamma\nd\n\n{kitchen}[Drink] <milk> (1)\n",
             "3": f"Beta\nd\n\n{sofa}", "4": f"Delta\nd\n\n{sofa}[StandUp]\n",
             "5": f"Alpha\nd\n\n{kitchen}[Walk] <table> (1)\n"}
    ds = ActivityDataset.from_texts(texts)
    matrix = similarity_matrix(ds, pairwise_lcs(ds)[1])
    order = matrix.activities
    assert abs(order.index("alpha") - order.index("gamma")) == 1
    assert abs(order.index("beta") - order.index("delta")) == 1


def test_fig_4_counts(tiny):
    assert action_counts(tiny) == [("Walk", 3), ("Sit", 2), ("Watch", 2), ("Grab", 1),
                                   ("Read", 1), ("SwitchOn", 1)]
    assert object_counts(tiny) == [("tv", 5), ("book", 3), ("sofa", 2)]
    assert object_counts(tiny, top=1) == [("tv", 5)]


def test_compute_stats_reports_progress(tiny):
    seen = []
    stats = compute_stats(tiny, progress=lambda done, total: seen.append((done, total)))
    assert seen[-1] == (3, 3)
    assert stats.within_activity == pytest.approx(0.75)
    assert stats.between_activities == 0.0
    assert stats.summary.programs == 3 and stats.name == "tiny"


@pytest.mark.dataset
def test_real_dataset_figures(real_data):
    stats = compute_stats(ActivityDataset.load(real_data))
    s = stats.summary
    assert (s.programs, s.activities) == (518, 26)
    assert s.avg_steps == pytest.approx(9.09, abs=0.01)
    assert stats.within_activity > 5 * stats.between_activities
    assert stats.actions[0] == ("Find", 1315)
    assert len(stats.similarity.activities) == 26
