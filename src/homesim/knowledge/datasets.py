"""Activity data sets: programs with a title (the activity) and a description.

Glossary:
    activity: what a program is for, its title (``Watch TV``); programs are grouped by the
        normalized title (`normalize_title`: lower case, single spaces, no end punctuation).
    ActivityPrograms format: a text file holding a title line, a description (one or more
        lines), a blank line, then one step per line.
    JSONL format: one `ActivityProgram` per line, the format `homesim synth` writes and
        every loader reads: ``{"id", "title", "description", "program": [step lines],
        "graph": path or null, "home": built-in home or null, "bindings": [[class name,
        instance, node id], ...]}``; ``graph``, ``home`` and ``bindings`` may be left out
        (docs/knowledge.md describes each field).

`ActivityDataset.load` reads a file or folder in either format, or the fetched eai-eval
data set (518 programs with initial and final graphs). Every program must have a title,
a description and at least one step; a file that breaks this, is not UTF-8, or does not
parse gives a `DataError` (or `ProgramError`) naming the file and line.
"""

from __future__ import annotations

import json
import random
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass, field, replace
from functools import lru_cache
from pathlib import Path
from typing import Any, overload

from homesim.errors import DataError, HomesimError, LimitError
from homesim.files import atomic_write, read_text_limited
from homesim.knowledge.fetch import dataset_dir, verify
from homesim.limits import MAX_DATA_FILE_BYTES
from homesim.program.bindings import Bindings
from homesim.program.model import ObjectRef, Program, Step
from homesim.program.parse import parse_program, parse_steps
from homesim.world.graph import EnvironmentGraph
from homesim.world.homes import load_home

SPLITS = ("train", "val", "test")


def normalize_title(title: str) -> str:
    """The activity a title names: lower case, single spaces, no trailing punctuation.

    >>> normalize_title("  Watch  TV. ")
    'watch tv'
    """
    return " ".join(title.lower().split()).rstrip(".!?;:, ")


@dataclass(frozen=True)
class ActivityProgram:
    """One program of a data set: the one record type of every data set homesim reads or
    writes (real, synthetic, learning examples).

    Attributes:
        id: unique within its data set (file stem or path relative to the folder, or the
            JSONL ``id``; ``synth-<seed>-<index>`` for synthetic programs).
        program: the parsed program, with its title and description.
        source: where it was read from (``path`` or ``path:line``), or ``synth``.
        graph_path: JSON file with ``init_graph`` and ``final_graph``, if the data set has one.
        home: the built-in home the program belongs to (`homesim.load_home`), if any.
        bindings: (class name, instance) -> node id of the program's objects in its home
            (synthetic programs; learning examples of ungrounded real programs).
    """

    id: str
    program: Program
    source: str = ""
    graph_path: Path | None = None
    home: str | None = None
    bindings: Bindings = field(default_factory=Bindings, compare=False)

    @property
    def title(self) -> str:
        return self.program.title

    @property
    def description(self) -> str:
        return self.program.description

    @property
    def text(self) -> str:
        """Title and description as one text (what a description -> program model reads)."""
        return f"{self.program.title}. {self.program.description}".strip()

    @property
    def activity(self) -> str:
        """The normalized title, used to group programs by activity."""
        return normalize_title(self.program.title)

    def graph_dicts(self) -> tuple[dict, dict]:
        """The stored initial and final graphs as raw VirtualHome dicts."""
        if self.graph_path is None:
            raise DataError(f"{self.source or self.id}: no stored graphs for this program")
        try:
            data = json.loads(self.graph_path.read_text(encoding="utf-8"))
            return data["init_graph"], data["final_graph"]
        except (OSError, ValueError, KeyError, TypeError) as e:
            raise DataError(f"{self.graph_path}: cannot read stored graphs ({e})") from None

    def graphs(self) -> tuple[EnvironmentGraph, EnvironmentGraph]:
        """The stored initial and final graphs; `DataError` if this program has none."""
        init, final = self.graph_dicts()
        where = str(self.graph_path)
        return (EnvironmentGraph.from_dict(init, f"{where}:init_graph"),
                EnvironmentGraph.from_dict(final, f"{where}:final_graph"))

    def graph(self) -> EnvironmentGraph:
        """The home the program starts in: its stored initial graph, else its built-in home
        (loaded once per process and shared: read-only)."""
        if self.graph_path is not None:
            return _stored_initial_graph(str(self.graph_path))
        if self.home is not None:
            return load_home(self.home)
        raise DataError(f"{self.source or self.id}: no home or stored graph for this program")

    def ungrounded(self) -> ActivityProgram:
        """This record with node ids taken out of the program and kept in `bindings`."""
        bindings = dict(self.bindings)
        steps = []
        for step in self.program.steps:
            for ref in step.args:
                if ref.node_id is not None:
                    bindings.setdefault(ref.key, ref.node_id)
            steps.append(Step(step.action, tuple(ObjectRef(r.name, r.instance)
                                                 for r in step.args)))
        return replace(self, program=replace(self.program, steps=tuple(steps)),
                       bindings=Bindings(bindings))

    def to_json(self) -> dict:
        """The JSONL record of this program (fields in the module docstring)."""
        record: dict = {"id": self.id, "title": self.title, "description": self.description,
                        "program": [str(s) for s in self.program.steps],
                        "graph": str(self.graph_path) if self.graph_path else None,
                        "home": self.home}
        if self.bindings:
            record["bindings"] = [[n, i, v] for (n, i), v in sorted(self.bindings.items())]
        return record

    @classmethod
    def from_json(cls, record: object, where: str = "", base: Path | None = None
                  ) -> ActivityProgram:
        """The record `to_json` wrote; `DataError` naming `where` if it is malformed.

        A relative ``graph`` path is read from `base` (the JSONL file's folder).
        """
        return _from_record(record, where or "record", base or Path("."))


@lru_cache(maxsize=1024)
def _stored_initial_graph(path: str) -> EnvironmentGraph:
    init, _ = ActivityProgram("", Program(), graph_path=Path(path)).graph_dicts()
    return EnvironmentGraph.from_dict(init, f"{path}:init_graph")


def _check(program: Program, where: str) -> Program:
    if not program.title:
        raise DataError(f"{where}: no title (expected a title line, a description, a blank "
                        "line, then the steps)")
    if not program.description:
        raise DataError(f"{where}: no description (expected it on the line after the title)")
    if not program.steps:
        raise DataError(f"{where}: empty program (no steps after the description)")
    return program


def _read_text(path: Path) -> str:
    """A file's UTF-8 text (a BOM is dropped); `DataError` naming the file if unreadable."""
    try:
        return read_text_limited(path, MAX_DATA_FILE_BYTES, "MAX_DATA_FILE_BYTES")
    except LimitError:
        raise
    except HomesimError as e:
        raise DataError(str(e)) from None


def read_program_file(path: Path) -> Program:
    """Read one ActivityPrograms file; `DataError` naming the file if it is bad."""
    return _check(parse_program(_read_text(path), source=str(path)), str(path))


def real_programs(directory: Path | None = None, check: bool = False) -> list[ActivityProgram]:
    """The real program data set (fetched by `homesim.knowledge.fetch`): all its programs,
    sorted by id, each with its stored graphs; `check` verifies checksums first.

    Ids are file stems, e.g. ``file1003_2`` (script 1003, second annotation); refs are
    grounded (``<computer> (1.417)``).
    """
    directory = directory or dataset_dir()
    if check:
        verify(directory)
    programs_dir = directory / "programs"
    if not programs_dir.is_dir():
        raise DataError(f"{directory}: the real data set is not here; run 'homesim data fetch'")
    return [ActivityProgram(path.stem, read_program_file(path), str(path),
                            directory / "graphs" / f"{path.stem}.json")
            for path in sorted(programs_dir.glob("*.txt"))]


class ActivityDataset(Sequence[ActivityProgram]):
    """An ordered, read-only collection of `ActivityProgram` values.

    >>> ds = ActivityDataset.from_texts({"a": "Watch TV\\nI watch.\\n\\n[Walk] <tv> (1)"})
    >>> len(ds), ds[0].activity
    (1, 'watch tv')
    """

    def __init__(self, items: Sequence[ActivityProgram], name: str = "",
                 skipped: Sequence[str] = ()):
        ids = [item.id for item in items]
        if len(set(ids)) != len(ids):
            dup = next(i for i in ids if ids.count(i) > 1)
            raise DataError(f"{name or 'data set'}: duplicate program id {dup!r}")
        self._items = tuple(items)
        self.name = name
        self.skipped: tuple[str, ...] = tuple(skipped)
        """One error line per file that was skipped (``skip_bad=True``)."""

    # -- Sequence --------------------------------------------------------------------

    def __len__(self) -> int:
        return len(self._items)

    @overload
    def __getitem__(self, index: int) -> ActivityProgram: ...
    @overload
    def __getitem__(self, index: slice) -> ActivityDataset: ...

    def __getitem__(self, index: int | slice) -> ActivityProgram | ActivityDataset:
        if isinstance(index, slice):
            return ActivityDataset(self._items[index], self.name)
        return self._items[index]

    def __iter__(self) -> Iterator[ActivityProgram]:
        return iter(self._items)

    def __repr__(self) -> str:
        return f"ActivityDataset({self.name!r}, {len(self)} programs)"

    @property
    def programs(self) -> list[Program]:
        return [item.program for item in self._items]

    def by_activity(self) -> dict[str, list[ActivityProgram]]:
        """Programs grouped by normalized title, activities in order of first appearance."""
        groups: dict[str, list[ActivityProgram]] = {}
        for item in self._items:
            groups.setdefault(item.activity, []).append(item)
        return groups

    # -- loading -------------------------------------------------------------------------

    @classmethod
    def from_texts(cls, texts: dict[str, str], name: str = "") -> ActivityDataset:
        """Build from ``{id: ActivityPrograms text}`` (handy in tests and notebooks)."""
        items = [ActivityProgram(i, _check(parse_program(t, source=i), i), i)
                 for i, t in texts.items()]
        return cls(items, name)

    @classmethod
    def from_file(cls, path: str | Path) -> ActivityDataset:
        """One ActivityPrograms file as a one-program data set."""
        path = Path(path)
        return cls([ActivityProgram(path.stem, read_program_file(path), str(path))], str(path))

    @classmethod
    def from_folder(cls, path: str | Path, skip_bad: bool = False) -> ActivityDataset:
        """Every ``*.txt`` under a folder (recursively, sorted); ids are relative paths.

        With `skip_bad`, bad files are left out and their error lines kept in `skipped`.
        """
        root = Path(path)
        if not root.is_dir():
            raise DataError(f"{root}: not a folder")
        items, skipped = [], []
        for file in sorted(root.rglob("*.txt")):
            try:
                program = read_program_file(file)
            except HomesimError as e:
                if not skip_bad:
                    raise
                skipped.append(str(e))
                continue
            rel = file.relative_to(root).with_suffix("").as_posix()
            items.append(ActivityProgram(rel, program, str(file)))
        if not items and not skipped:
            raise DataError(f"{root}: no program files (*.txt) here")
        return cls(items, str(root), skipped)

    @classmethod
    def from_jsonl(cls, path: str | Path, skip_bad: bool = False) -> ActivityDataset:
        """A JSONL file (see the module docstring); errors name the file and line."""
        path = Path(path)
        text = _read_text(path)
        items, skipped = [], []
        for lineno, line in enumerate(text.splitlines(), 1):
            if not line.strip():
                continue
            where = f"{path}:{lineno}"
            try:
                items.append(_from_record(_json_line(line, where), where, path.parent))
            except HomesimError as e:
                if not skip_bad:
                    raise
                skipped.append(str(e))
        if not items and not skipped:
            raise DataError(f"{path}: no programs in this file")
        return cls(items, str(path), skipped)

    @classmethod
    def real(cls, directory: Path | None = None) -> ActivityDataset:
        """The fetched eai-eval data set: 518 programs, each with its stored graphs."""
        return cls(real_programs(directory), "eai-eval-1.0.5")

    @classmethod
    def load(cls, path: str | Path | None = None, skip_bad: bool = False) -> ActivityDataset:
        """Load whatever `path` is: None or an eai-eval folder (``programs/`` and
        ``graphs/``) -> `real`; another folder -> `from_folder`; ``*.jsonl`` ->
        `from_jsonl`; another file -> `from_file`."""
        if path is None:
            return cls.real()
        path = Path(path)
        if not path.exists():
            raise DataError(f"{path}: no such file or folder")
        if path.is_dir():
            if (path / "programs").is_dir() and (path / "graphs").is_dir():
                return cls.real(path)
            return cls.from_folder(path, skip_bad)
        if path.suffix == ".jsonl":
            return cls.from_jsonl(path, skip_bad)
        return cls.from_file(path)

    # -- saving and splitting ------------------------------------------------------------

    def to_jsonl(self, path: str | Path, overwrite: bool = False) -> Path:
        """Write the data set as JSONL; refuses to replace a file unless `overwrite`."""
        path = Path(path)
        if path.exists() and not overwrite:
            raise DataError(f"{path}: already exists (pass overwrite=True to replace it)")
        write_jsonl(self._items, path, force=overwrite)
        return path

    def split(self, seed: int = 0, fractions: tuple[float, float, float] = (0.8, 0.1, 0.1)
              ) -> dict[str, ActivityDataset]:
        """Deterministic train/val/test splits, stratified by activity.

        Activities and the programs within each are shuffled with `seed`; then each
        program goes to the split furthest below its share of the programs dealt so far.
        So every split gets its fraction of the whole (to within one program), each
        activity is spread over the splits in proportion, and activities with a single
        program are spread over the splits too rather than all landing in train.
        """
        if len(fractions) != 3 or any(f < 0 for f in fractions) or sum(fractions) <= 0:
            raise ValueError(f"fractions must be three non-negative numbers, got {fractions}")
        total = sum(fractions)
        shares = [f / total for f in fractions]
        rng = random.Random(seed)
        groups = [sorted(g, key=lambda item: item.id) for _, g in
                  sorted(self.by_activity().items())]
        rng.shuffle(groups)
        chosen: list[list[ActivityProgram]] = [[], [], []]
        dealt = 0
        for group in groups:
            rng.shuffle(group)
            for item in group:
                dealt += 1
                deficits = [share * dealt - len(c) for share, c in zip(shares, chosen,
                                                                       strict=True)]
                chosen[max(range(3), key=lambda k: (deficits[k], -k))].append(item)
        order = {item.id: i for i, item in enumerate(self._items)}
        return {name: ActivityDataset(sorted(c, key=lambda item: order[item.id]),
                                      f"{self.name}[{name}]")
                for name, c in zip(SPLITS, chosen, strict=True)}


_REQUIRED = ("title", "description", "program")


def write_jsonl(items: Iterable[ActivityProgram], path: str | Path, force: bool = False) -> int:
    """Write records as JSONL, atomically (`homesim.files`); return how many were written.

    `items` may be a generator: nothing replaces `path` until the last record is written.
    """
    count = 0
    with atomic_write(path, "w", force=force) as f:
        for item in items:
            f.write(json.dumps(item.to_json(), ensure_ascii=False) + "\n")
            count += 1
    return count


def _json_line(line: str, where: str) -> object:
    try:
        return json.loads(line)
    except ValueError as e:
        raise DataError(f"{where}: not valid JSON ({e})") from None


def _one_line(text: str) -> str:
    """Join wrapped lines as the ActivityPrograms parser does; keep spacing within a line."""
    return " ".join(line.strip() for line in text.splitlines() if line.strip())


def _from_record(record: object, where: str, base: Path) -> ActivityProgram:
    if not isinstance(record, dict):
        raise DataError(f"{where}: expected a JSON object, got {type(record).__name__}")
    missing = [k for k in _REQUIRED if k not in record]
    if missing:
        raise DataError(f"{where}: missing {', '.join(missing)}")
    steps = record["program"]
    if isinstance(steps, str):
        steps = steps.splitlines()
    if not isinstance(steps, list) or not all(isinstance(s, str) for s in steps):
        raise DataError(f"{where}: 'program' must be a list of step lines")
    title, description = record["title"], record["description"]
    if not isinstance(title, str) or not isinstance(description, str):
        raise DataError(f"{where}: 'title' and 'description' must be strings")
    title, description = _one_line(title), _one_line(description)
    if not title:
        raise DataError(f"{where}: no title")
    parsed = parse_steps(steps, source=where)
    program = _check(Program(parsed.steps, title, description), where)
    graph = record.get("graph")
    graph_path = (base / graph) if isinstance(graph, str) and graph else None
    home = record.get("home")
    if home is not None and not isinstance(home, str):
        raise DataError(f"{where}: 'home' must be a built-in home name or null")
    return ActivityProgram(str(record.get("id") or where.rsplit(":", 1)[-1]), program, where,
                           graph_path, home or None, _bindings(record.get("bindings"), where))


def _bindings(value: Any, where: str) -> Bindings:
    """``[[class name, instance, node id], ...]`` as `Bindings`; `DataError` if malformed.

    `value` is raw JSON (hence `Any`); every item is checked here.
    """
    if value is None:
        return Bindings()
    try:
        out: dict[tuple[str, int], int] = {}
        for name, instance, node in value:
            if not isinstance(name, str) or type(instance) is not int or type(node) is not int:
                raise TypeError
            out[(name, instance)] = node
        return Bindings(out)
    except (TypeError, ValueError):
        raise DataError(f"{where}: 'bindings' must be a list of [class name, instance, "
                        "node id]") from None

