"""Write a program for a description: the reranker of the evaluation, fitted on every real
program, as a tool (``homesim learn write``, ``POST /api/write``, `write_program`).

The model is `reranker.Reranker` fitted on the 518 real programs (queries hide only their own
program, as on the stratified split: docs/results.md gives what it scores on unseen
descriptions). Fitting takes about 90 s on an idle 2-core machine and is done once, by
``homesim learn fit-writer`` (`FIT_STEP`; ``make test`` runs it after ``homesim data
fetch``); the fitted model is kept in the data directory (``$HOMESIM_DATA/models``, a
pickle that only homesim writes), keyed by what it was fitted from, and read back by later
calls. The server never fits it (``POST /api/write`` says which step to run instead).
A written program is ungrounded (``<television> (1)``) and is run in the home asked for
through `run_program`: of the best `RerankConfig.check_executable` candidates the first
that runs there is written.
"""

from __future__ import annotations

import hashlib
import pickle
import threading
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import Any

import numpy as np

from homesim.errors import HomesimError, LimitError
from homesim.files import write_bytes
from homesim.ground.pipeline import Run, run_program
from homesim.knowledge.datasets import ActivityProgram
from homesim.knowledge.fetch import data_root
from homesim.learn.data import Example, real_examples
from homesim.learn.embeddings import lone_sentence_vectors, preload_sentence_vectors
from homesim.learn.execution import repaired_in
from homesim.learn.rerank.reranker import Reranker
from homesim.limits import MAX_DESCRIPTION_CHARS
from homesim.program.model import Program
from homesim.program.parse import step_lines
from homesim.version import __version__
from homesim.world.graph import EnvironmentGraph
from homesim.world.homes import load_home

FORMAT = 9
"""Bumped when what a stored model holds, or the candidates its trees were fitted on,
change (a stored model of another format is fitted again); 2: the reranker's medians; 3:
its inserter of the steps the text says; 4: the inserter's phrase-to-clause cosines; 5: its
deleter, kept where its own cross-validation finds it pays; 6: the deleter's
phrase-to-text cosines; 7: `homesim.learn` as packages (the pickled classes moved; the
reranker lost its unused likelihood field); 8: the settings saved with the model
(`RerankConfig` in its bank, the title vote's temperature in the writer); 9: what the text
supports (`support`: trees also fitted on descriptions cut short, the typical program as a
candidate and a feature, its margins by support level)."""
SEED = 0
"""Seed of preparation and grounding when a written program is run."""


@dataclass(frozen=True)
class Written:
    """A written program and its run in the home it was written for.

    Attributes:
        program: ungrounded steps, with the title and description they were written for.
        title_given: False when the title was guessed from the training descriptions
            nearest to the text (none was given).
        run: `run_program` of the program in the home.
    """

    program: Program
    title_given: bool
    run: Run

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the program text, its steps, the title and whether it was given, and
        the run (`Run.to_dict`, its ``line`` fields those of the program text)."""
        text = str(self.program)
        return {"program": text, "steps": [str(s) for s in self.program.steps],
                "title": self.program.title, "title_given": self.title_given,
                "executable": self.run.executable, "run": self.run.to_dict(step_lines(text))}


@dataclass
class ProgramWriter:
    """The fitted reranker (with its settings, `Reranker.config`), the key of the examples it
    was fitted on, and the temperature of its title vote; pickled whole."""

    reranker: Reranker
    key: str
    title_tau: float = 0.05
    """Temperature of the title vote (`guess_title`): leave-one-out over the real programs
    it names the activity of 87.6% of descriptions (the nearest description's title: 84.2%;
    tau .02 87.1%, .1 85.7%; `tools/title_guess.py`)."""

    @classmethod
    def fit(cls, examples: list[Example]) -> ProgramWriter:
        """Fit on `examples` (each queried against the others, its own program hidden)."""
        if not examples:
            raise HomesimError("no examples to fit the program writer on")
        preload_sentence_vectors([t for e in examples for t in (e.description, e.title)])
        return cls(Reranker.fit(examples, "program"), examples_key(examples))

    def write(self, description: str, graph: EnvironmentGraph, title: str | None = None,
              seed: int = SEED) -> Written:
        """The program for `description` (and `title`; without one, or a blank one,
        `guess_title`) that runs in `graph`, if one of the best candidates does."""
        description, asked = check_text("description", description), check_title(title)
        # embedded on its own, so the floats (and the choice) are the same in every process
        desc_vector = lone_sentence_vectors([description])[0]
        title = asked if asked is not None else self.guess_title(desc_vector)
        given = asked is not None
        query = ActivityProgram("query", Program((), title=title, description=description))

        def runs(p: Program) -> bool:
            return run_program(p, graph, seed=seed, repair=False).executable

        vectors = (desc_vector, self.title_vector(title))
        chosen = self.reranker.choose(query, runs, vectors,
                                      repair=lambda p: repaired_in(p, graph, seed))
        program = Program(chosen.steps, title=title, description=description)
        return Written(program, given, run_program(program, graph, seed=seed, trace=True,
                                                   repair=False))

    def title_vector(self, title: str) -> np.ndarray:
        """A title's sentence vector, the same in every process: a training title's is the
        one the model was fitted with, another is embedded on its own (a text's floats
        depend on the batch it is embedded in, and the choice can follow)."""
        bank = self.reranker.bank
        known = next((i for i, e in enumerate(bank.train) if e.title == title), None)
        return bank.title[known] if known is not None else lone_sentence_vectors([title])[0]

    def guess_title(self, desc_vector: np.ndarray) -> str:
        """The activity whose training descriptions are nearest to a description's
        sentence vector (`vote_titles`)."""
        bank = self.reranker.bank
        return vote_titles((bank.desc @ desc_vector)[None], [e.title for e in bank.train],
                           self.title_tau)[0]


def vote_titles(sims: np.ndarray, titles: list[str], tau: float) -> list[str]:
    """For each row of `sims` (queries x training descriptions, MiniLM cosines; -inf for
    one a query may not see), the title the training descriptions vote for with weights
    softmax(cosine / `tau`); ties go to the first title in sorted order."""
    names = sorted(set(titles))
    column = {name: i for i, name in enumerate(names)}
    weights = np.exp((sims - sims.max(axis=1, keepdims=True)) / tau)
    votes = np.zeros((len(sims), len(names)))
    for j, title in enumerate(titles):
        votes[:, column[title]] += weights[:, j]
    return [names[int(k)] for k in votes.argmax(axis=1)]


def check_text(field: str, text: str) -> str:
    """`text` on one line with spaces folded; a clear error when it is empty or over
    `MAX_DESCRIPTION_CHARS`."""
    if len(text) > MAX_DESCRIPTION_CHARS:
        raise LimitError(f"{field}: {len(text)} characters, over the limit of "
                         f"{MAX_DESCRIPTION_CHARS} (MAX_DESCRIPTION_CHARS)",
                         "MAX_DESCRIPTION_CHARS")
    try:
        text.encode("utf-8")
    except UnicodeEncodeError as e:  # a lone surrogate: from bytes not UTF-8, or "\ud800"
        raise HomesimError(f"{field}: not valid text (character {e.start + 1} is not "
                           "Unicode; give UTF-8 text)") from None
    folded = " ".join(text.split())
    if not folded:
        raise HomesimError(f"{field}: empty")
    return folded


def check_title(title: str | None) -> str | None:
    """A title as `check_text` folds it; None for none or a blank one (to be guessed)."""
    return None if title is None or not title.strip() else check_text("title", title)


def examples_key(examples: list[Example]) -> str:
    """A digest of what a writer is fitted from: the examples, the model format, the
    versions of homesim and scikit-learn."""
    import sklearn  # deferred: scikit-learn takes seconds to import

    h = hashlib.sha256(f"{FORMAT} {__version__} {sklearn.__version__}".encode())
    for e in examples:
        h.update(f"\0{e.title}\0{e.description}\0{e.program}".encode())
    return h.hexdigest()[:16]


def model_path(key: str, root: Path | None = None) -> Path:
    """Where the writer fitted with `key` is kept."""
    return (root or data_root()) / "models" / f"writer-{key}.pkl"


FIT_STEP = "homesim learn fit-writer"
"""The command that fits the writer's model once, ahead of any request or test."""


class WriterNotFitted(HomesimError):
    """The writer's model is not in the data directory, and was not to be fitted here."""


def is_fitted(root: Path | None = None) -> bool:
    """Whether the writer's model on the real programs is in the data directory (fitted by
    `FIT_STEP`); reads the real programs for their key, not the model."""
    return model_path(examples_key(real_examples()), root).is_file()


def load_writer(examples: list[Example] | None = None, root: Path | None = None,
                fit: bool = True) -> ProgramWriter:
    """The writer fitted on `examples` (default: the real programs, which need ``homesim
    data fetch``), read from the data directory when it was fitted before, else fitted and
    kept there (or, without `fit`, `WriterNotFitted` naming `FIT_STEP`)."""
    if examples is None:
        examples = real_examples()
    path = model_path(examples_key(examples), root)
    stored = _read_stored(path)
    if stored is not None:
        return stored
    if not fit:
        raise WriterNotFitted(f"the program writer's model is not built yet: run "
                              f"'{FIT_STEP}' once (about 90 s)")
    writer = ProgramWriter.fit(examples)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        write_bytes(path, pickle.dumps(writer, protocol=pickle.HIGHEST_PROTOCOL))
    except OSError:
        pass  # a read-only data directory: fitted again next time
    return writer


def _read_stored(path: Path) -> ProgramWriter | None:
    """The writer kept at `path`, if it is one fitted with the key its name gives (a file
    that cannot be read as one is fitted again and replaced)."""
    try:
        writer = pickle.loads(path.read_bytes())
    except Exception:  # missing, truncated, or written by another version: fit again
        return None
    ok = isinstance(writer, ProgramWriter) and writer.key == path.stem.removeprefix("writer-")
    return writer if ok else None


_LOADING = threading.Lock()


@cache
def _real_writer(fit: bool) -> ProgramWriter:
    return load_writer(fit=fit)


def real_writer(fit: bool = True) -> ProgramWriter:
    """The writer fitted on the real programs, once per process (threads wait for the
    first to load it); without `fit`, `WriterNotFitted` when it was never fitted."""
    with _LOADING:
        return _real_writer(fit)


def write_program(description: str, home: EnvironmentGraph | str = "scene1",
                  title: str | None = None, seed: int = SEED) -> Written:
    """Write a program for `description` (and `title`) and run it in `home` (a built-in
    home's name or a graph), with the writer fitted on the real programs."""
    check_text("description", description)  # bad text is refused before the model loads
    check_title(title)
    graph = load_home(home) if isinstance(home, str) else home
    return real_writer().write(description, graph, title=title, seed=seed)
