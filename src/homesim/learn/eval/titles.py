"""Title -> program benchmark on the real data, in the form of Huang et al. (2022).

A planner reads ``Task: Watch TV`` (the program's title, nothing else) and writes steps.
Predictions are scored as the learning table scores them (`homesim.learn.eval.scores`):
normalised LCS of actions, objects and steps against the annotated program, and
executability (`homesim.run_program` in the program's own initial graph, preparing and
grounding the ungrounded prediction). The split is the learning split of the real data
(`homesim.learn.data.split`, 70/10/20 by activity, seeded), so the baselines of
`homesim.learn.eval.baselines` and an LLM's answers are scored on the same test programs.

Predictions from elsewhere: a JSON object ``{program id: program text}`` (ids as in
`prompts`), program text in homesim's step syntax (``[Walk] <tv> (1)``, one per line).
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

from homesim.errors import DataError, HomesimError
from homesim.learn.data import Example, Splits, real_examples, split
from homesim.learn.embeddings import sentence_vectors
from homesim.learn.eval import baselines
from homesim.learn.eval.scores import Scores, score
from homesim.learn.execution import executable
from homesim.program.model import Program
from homesim.program.parse import parse_program

BASELINES = ("random_sampling", "random_retrieval", "nn_retrieval")


def prompt(example: Example) -> str:
    """The planner's whole input: ``Task: <title>``."""
    return f"Task: {example.title}"


def title_only(example: Example) -> Example:
    """The example with its title as its only text: the description is the title too, as
    when a writer is asked with nothing but a title (``homesim learn write "Watch TV"
    --title "Watch TV"``); the program, its home and bindings are kept for scoring."""
    return replace(example, program=replace(example.program,
                                            description=example.program.title))


def title_splits(seed: int = 0, directory: Path | None = None) -> Splits:
    """The real data's learning split, each example reduced to its title."""
    examples = [replace(e, program=replace(e.program, description=""))
                for e in real_examples(directory)]
    return split("real-titles", examples, seed)


def prompts(splits: Splits) -> list[dict[str, str]]:
    """``{id, prompt}`` of every test program, for a planner to answer."""
    return [{"id": e.id, "prompt": prompt(e)} for e in splits.test]


def baseline(name: str, splits: Splits, seed: int = 0) -> list[Program]:
    """Predictions of one of `BASELINES` for the test programs, from their titles."""
    if name == "random_sampling":
        return baselines.random_sampling(splits.train, splits.test, seed)
    if name == "random_retrieval":
        return baselines.random_retrieval(splits.train, splits.test, seed)
    if name == "nn_retrieval":
        train = sentence_vectors([prompt(e) for e in splits.train])
        test = sentence_vectors([prompt(e) for e in splits.test])
        return baselines.nn_retrieval(splits.train, splits.test, train, test)
    raise HomesimError(f"unknown baseline {name!r} (one of {', '.join(BASELINES)})")


def read_predictions(path: Path, splits: Splits) -> list[Program]:
    """Predictions for the test programs from a JSON ``{id: program text}`` file; a missing
    id is an empty program (scored as not executable)."""
    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, ValueError) as e:
        raise DataError(f"{path}: cannot read predictions ({e})") from None
    if not isinstance(data, dict):
        raise DataError(f"{path}: expected a JSON object {{program id: program text}}")
    out = []
    for example in splits.test:
        text = data.get(example.id, "")
        if not isinstance(text, str):
            raise DataError(f"{path}: {example.id}: the program must be text")
        out.append(parse_program(text, source=f"{path}:{example.id}") if text.strip()
                   else Program(()))
    return out


def evaluate(preds: list[Program], splits: Splits,
             runs: Callable[[Program, Example], bool] | None = None) -> Scores:
    """LCS against the test programs and executability in their homes."""
    runs = runs or executable
    flags = [bool(p.steps) and runs(p, e) for p, e in zip(preds, splits.test, strict=True)]
    return score(preds, [e.program for e in splits.test], flags)
