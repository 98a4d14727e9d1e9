"""Dataset analysis: the VirtualHome paper's Table 1 and Fig. 4 for any activity data set.

    Table 1(a): programs, average steps, average sentences and words per description.
    Table 1(b): for chosen activities, the number of programs and the mean pairwise LCS
                (length and normalized) between programs of that activity.
    Table 1(c): the activity-by-activity similarity matrix: entry (i, j) is the mean
                normalized LCS between the programs of activity i and those of activity j
                (distinct pairs only on the diagonal), rows block-sorted by clustering.
    Fig. 4:     how often each action and each object class occurs, most common first.

All LCS figures here compare whole steps (action and object classes; see
`homesim.program.metrics`). This module computes values; `homesim.knowledge.stats_plots`
draws them and the CLI (``homesim data stats``) prints them. Needs the ``stats`` extra
(numpy, scipy).
"""

from __future__ import annotations

import re
from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from homesim.knowledge.datasets import ActivityDataset, normalize_title
from homesim.program.metrics import lcs_length, step_tokens

Progress = Callable[[int, int], None]
"""Called as progress(done, total) while comparing programs."""

_SENTENCE_END = re.compile(r"[.!?]+")
_WORD = re.compile(r"[^\W_]+(?:['’][^\W_]+)*")


def count_sentences(text: str) -> int:
    """Sentences in a description: pieces between ``.``, ``!`` or ``?`` that hold a word.

    A description without end punctuation is one sentence.

    >>> count_sentences("Go to the kitchen. Make coffee!  ")
    2
    """
    return sum(1 for piece in _SENTENCE_END.split(text) if _WORD.search(piece))


def count_words(text: str) -> int:
    """Words in a description: runs of letters or digits (``don't`` is one word).

    >>> count_words("I don't watch TV, I read 2 books.")
    8
    """
    return len(_WORD.findall(text))


@dataclass(frozen=True)
class DatasetSummary:
    """Table 1(a)."""

    programs: int
    activities: int
    avg_steps: float
    avg_sentences: float
    avg_words: float


@dataclass(frozen=True)
class ActivityLCS:
    """A row of Table 1(b): pairwise LCS between the programs of one activity."""

    activity: str
    programs: int
    pairs: int
    mean_lcs: float
    """Mean LCS length, in steps, over the distinct pairs (nan with fewer than 2 programs)."""
    mean_normalized_lcs: float
    """Mean LCS / longer program length over the same pairs."""


@dataclass(frozen=True)
class SimilarityMatrix:
    """Table 1(c): mean normalized LCS between activities, rows in block-sorted order."""

    activities: list[str]
    programs: list[int]
    values: np.ndarray  # (activities, activities); nan where there are no pairs


@dataclass(frozen=True)
class DatasetStats:
    """Everything ``homesim data stats`` reports for one data set."""

    name: str
    summary: DatasetSummary
    activity_lcs: list[ActivityLCS]
    within_activity: float
    """Mean normalized LCS over pairs of programs of the same activity."""
    between_activities: float
    """Mean normalized LCS over pairs of programs of different activities."""
    similarity: SimilarityMatrix
    actions: list[tuple[str, int]] = field(default_factory=list)
    objects: list[tuple[str, int]] = field(default_factory=list)


def summarize(dataset: ActivityDataset) -> DatasetSummary:
    """Table 1(a) for a data set."""
    n = len(dataset)
    if n == 0:
        return DatasetSummary(0, 0, 0.0, 0.0, 0.0)
    return DatasetSummary(
        programs=n,
        activities=len(dataset.by_activity()),
        avg_steps=sum(len(p.program) for p in dataset) / n,
        avg_sentences=sum(count_sentences(p.description) for p in dataset) / n,
        avg_words=sum(count_words(p.description) for p in dataset) / n,
    )


def pairwise_lcs(dataset: ActivityDataset, progress: Progress | None = None
                 ) -> tuple[np.ndarray, np.ndarray]:
    """LCS lengths and normalized LCS between every two programs, over steps.

    Returns two symmetric (programs, programs) arrays; the diagonals compare a program
    with itself (length, 1.0).
    """
    # Steps become small ints first: comparing ints is the cheapest equality in the DP.
    vocab: dict = {}
    seqs = [[vocab.setdefault(t, len(vocab)) for t in step_tokens(p.program)] for p in dataset]
    n = len(seqs)
    lengths = np.zeros((n, n), dtype=np.int32)
    normalized = np.ones((n, n), dtype=np.float64)
    for i in range(n):
        lengths[i, i] = len(seqs[i])
        for j in range(i + 1, n):
            common = lcs_length(seqs[i], seqs[j])
            longer = max(len(seqs[i]), len(seqs[j]))
            lengths[i, j] = lengths[j, i] = common
            normalized[i, j] = normalized[j, i] = common / longer if longer else 1.0
        if progress:
            progress(i + 1, n)
    return lengths, normalized


def _groups(dataset: ActivityDataset) -> dict[str, list[int]]:
    groups: dict[str, list[int]] = {}
    for index, item in enumerate(dataset):
        groups.setdefault(item.activity, []).append(index)
    return groups


def activity_lcs(dataset: ActivityDataset, lengths: np.ndarray, normalized: np.ndarray,
                 activities: Sequence[str] | None = None, min_programs: int = 2
                 ) -> list[ActivityLCS]:
    """Table 1(b) rows, from the arrays of `pairwise_lcs`.

    `activities` picks the rows (titles, normalized when matched); by default every
    activity with at least `min_programs` programs, most programs first.
    """
    groups = _groups(dataset)
    if activities is None:
        chosen = sorted((a for a, g in groups.items() if len(g) >= min_programs),
                        key=lambda a: (-len(groups[a]), a))
    else:
        chosen = [normalize_title(a) for a in activities]
    rows = []
    for activity in chosen:
        members = groups.get(activity, [])
        iu = np.triu_indices(len(members), k=1)
        idx = np.asarray(members, dtype=np.intp)
        pair_lengths = lengths[np.ix_(idx, idx)][iu] if len(members) > 1 else np.array([])
        pair_norm = normalized[np.ix_(idx, idx)][iu] if len(members) > 1 else np.array([])
        rows.append(ActivityLCS(
            activity, len(members), int(pair_lengths.size),
            float(pair_lengths.mean()) if pair_lengths.size else float("nan"),
            float(pair_norm.mean()) if pair_norm.size else float("nan")))
    return rows


def within_between(dataset: ActivityDataset, normalized: np.ndarray) -> tuple[float, float]:
    """Mean normalized LCS over same-activity pairs and over different-activity pairs."""
    labels = np.array([item.activity for item in dataset])
    iu = np.triu_indices(len(labels), k=1)
    same = labels[iu[0]] == labels[iu[1]]
    values = normalized[iu]
    within = float(values[same].mean()) if same.any() else float("nan")
    between = float(values[~same].mean()) if (~same).any() else float("nan")
    return within, between


def similarity_matrix(dataset: ActivityDataset, normalized: np.ndarray,
                      min_programs: int = 1) -> SimilarityMatrix:
    """Table 1(c) over activities with at least `min_programs` programs, block-sorted.

    The order comes from average-linkage clustering of the activities on distance
    1 - similarity, with optimal leaf ordering, so similar activities sit side by side
    and clusters show as blocks along the diagonal.
    """
    groups = {a: g for a, g in _groups(dataset).items() if len(g) >= min_programs}
    names = sorted(groups)
    k = len(names)
    values = np.full((k, k), np.nan)
    for a, name_a in enumerate(names):
        ia = np.asarray(groups[name_a], dtype=np.intp)
        for b in range(a, k):
            ib = np.asarray(groups[names[b]], dtype=np.intp)
            block = normalized[np.ix_(ia, ib)]
            if a == b:
                pairs = block[np.triu_indices(len(ia), k=1)]
                values[a, a] = pairs.mean() if pairs.size else np.nan
            else:
                values[a, b] = values[b, a] = block.mean()
    order = _block_order(values)
    return SimilarityMatrix([names[i] for i in order], [len(groups[names[i]]) for i in order],
                            values[np.ix_(order, order)])


def _block_order(values: np.ndarray) -> list[int]:
    k = len(values)
    if k < 3:
        return list(range(k))
    from scipy.cluster.hierarchy import leaves_list, linkage
    from scipy.spatial.distance import squareform

    distance = 1.0 - np.nan_to_num(values, nan=0.0)
    np.fill_diagonal(distance, 0.0)
    distance = np.clip((distance + distance.T) / 2, 0.0, None)
    tree = linkage(squareform(distance, checks=False), method="average", optimal_ordering=True)
    return [int(i) for i in leaves_list(tree)]


def action_counts(dataset: ActivityDataset, top: int | None = 50) -> list[tuple[str, int]]:
    """How many steps use each action (by its canonical name), most common first."""
    counts = Counter(step.action.name for p in dataset for step in p.program.steps)
    return sorted(counts.items(), key=lambda kv: (-kv[1], kv[0]))[:top]


def object_counts(dataset: ActivityDataset, top: int | None = 50) -> list[tuple[str, int]]:
    """How many object arguments name each class, most common first."""
    counts = Counter(ref.name for p in dataset for step in p.program.steps for ref in step.args)
    return sorted(counts.items(), key=lambda kv: (-kv[1], kv[0]))[:top]


def compute_stats(dataset: ActivityDataset, activities: Sequence[str] | None = None,
                  min_programs: int = 2, top: int = 50, progress: Progress | None = None
                  ) -> DatasetStats:
    """Everything for Table 1 and Fig. 4 (one pass of pairwise LCS over the programs)."""
    lengths, normalized = pairwise_lcs(dataset, progress)
    within, between = within_between(dataset, normalized)
    return DatasetStats(
        name=dataset.name,
        summary=summarize(dataset),
        activity_lcs=activity_lcs(dataset, lengths, normalized, activities, min_programs),
        within_activity=within,
        between_activities=between,
        similarity=similarity_matrix(dataset, normalized),
        actions=action_counts(dataset, top),
        objects=object_counts(dataset, top),
    )
