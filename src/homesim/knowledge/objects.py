"""Object knowledge: affordances, possible states, name equivalences, placements, sizes.

Glossary:
    class: an object class name as programs or homes spell it (``cup``, ``coffee_table``,
        ``coffeetable``); lower case, words joined by underscores.
    script name: the name a program uses (``fruit``); its equivalents are the scene classes
        a home may have for it (``apple``, ``banana``, ...).
    placement: where an object of a class may be put when a program needs one the home
        lacks: a destination class, ON or INSIDE, and an optional room.

The knowledge ships in the package (``builtin/objects.json.gz``), converted from the
VirtualHome resources by ``tools/convert_knowledge.py``; `load_kb` reads it once.

Class lookups forgive spelling: a name is normalized (lower case, spaces to underscores)
and, if still unknown, matched ignoring underscores (``bathroom_cabinet`` finds
``bathroomcabinet``). An unknown class has no properties, states, placements or size;
``cls in kb`` tells whether a class is known.
"""

from __future__ import annotations

import gzip
import json
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources
from pathlib import Path
from typing import Literal

from homesim.errors import DataError
from homesim.program.syntax import normalize_name

FORMAT = "homesim-objects/1"

# When a class can be in either state of a pair, the first is how a fresh object starts.
_DEFAULT_OF_PAIR: tuple[tuple[str, str], ...] = (
    ("OFF", "ON"), ("CLOSED", "OPEN"), ("CLEAN", "DIRTY"), ("PLUGGED_IN", "PLUGGED_OUT"),
)

Relation = Literal["ON", "INSIDE"]


@dataclass(frozen=True, slots=True)
class Placement:
    """A place an object may be put: ``Placement("table", "ON", None)``.

    Attributes:
        destination: class of the object it goes on or into.
        relation: ``"ON"`` or ``"INSIDE"``.
        room: class of the room it must be in, or None for any room.
    """

    destination: str
    relation: Relation
    room: str | None = None


def _squash(name: str) -> str:
    return name.lower().replace("_", "").replace(" ", "")


@dataclass(frozen=True, slots=True)
class _ClassFacts:
    properties: frozenset[str]
    states: frozenset[str]
    placements: tuple[Placement, ...]
    size: tuple[float, float, float] | None


class ObjectKB:
    """Read-only object knowledge, indexed by class.

    >>> kb = load_kb()
    >>> kb.has_property("cup", "GRABBABLE")
    True
    >>> sorted(kb.default_states("tv"))
    ['OFF', 'PLUGGED_IN']
    >>> kb.equivalents("fruit")[:3]
    ['fruit', 'watermelon', 'apple']
    """

    def __init__(self, classes: dict[str, _ClassFacts], equivalences: dict[str, list[str]]):
        self._classes = classes
        # Spellings that differ only in underscores, indexed once (lookups are hot in grounding).
        self._spellings: dict[str, list[str]] = {}
        for name in sorted(classes):  # sorted: the same name wins on every load
            self._spellings.setdefault(_squash(name), []).append(name)
        self._equivalences = equivalences
        self._script_names: dict[str, list[str]] = {}
        for script, scene_classes in equivalences.items():
            for cls in scene_classes:
                self._script_names.setdefault(cls, []).append(script)

    @classmethod
    def from_dict(cls, data: dict, source: str = "<dict>") -> ObjectKB:
        """Build from the content of an ``objects.json`` file; `DataError` if malformed."""
        if not isinstance(data, dict) or data.get("format") != FORMAT:
            raise DataError(f"{source}: not a homesim object knowledge file "
                            f"(expected format {FORMAT!r})")
        try:
            classes = {
                name: _ClassFacts(
                    properties=frozenset(facts["properties"]),
                    states=frozenset(facts["states"]),
                    placements=tuple(Placement(d, r, room) for d, r, room in facts["placements"]),
                    size=tuple(facts["size"]) if facts["size"] is not None else None,
                )
                for name, facts in data["classes"].items()
            }
            equivalences = {k: list(v) for k, v in data["equivalences"].items()}
        except (KeyError, TypeError, ValueError) as e:
            raise DataError(f"{source}: malformed object knowledge ({type(e).__name__}: {e})"
                            ) from None
        return cls(classes, equivalences)

    @classmethod
    def load(cls, path: str | Path) -> ObjectKB:
        """Read an ``objects.json`` or ``objects.json.gz`` file."""
        path = Path(path)
        try:
            raw = path.read_bytes()
            if path.suffix == ".gz":
                raw = gzip.decompress(raw)
            data = json.loads(raw.decode("utf-8"))
        except (OSError, ValueError, EOFError) as e:
            raise DataError(f"{path}: cannot read object knowledge ({e})") from None
        return cls.from_dict(data, str(path))

    # -- lookup -------------------------------------------------------------------------

    def resolve(self, cls: str) -> str | None:
        """The known class a name stands for (spelling forgiven), or None.

        >>> load_kb().resolve("Bathroom Cabinet")
        'bathroom_cabinet'
        """
        name = normalize_name(cls)
        if name in self._classes:
            return name
        spellings = self._spellings.get(_squash(name))
        return spellings[0] if spellings else None

    def __contains__(self, cls: object) -> bool:
        return isinstance(cls, str) and self.resolve(cls) is not None

    def __len__(self) -> int:
        return len(self._classes)

    def _facts(self, cls: str) -> _ClassFacts | None:
        name = self.resolve(cls)
        return None if name is None else self._classes[name]

    def classes(self) -> list[str]:
        """Every known class, sorted."""
        return sorted(self._classes)

    # -- affordances and states ------------------------------------------------------------

    def properties(self, cls: str) -> frozenset[str]:
        """The affordances of a class (GRABBABLE, CAN_OPEN, ...); empty if unknown."""
        facts = self._facts(cls)
        return facts.properties if facts else frozenset()

    def has_property(self, cls: str, prop: str) -> bool:
        """Whether a class has an affordance, e.g. ``has_property("cup", "GRABBABLE")``."""
        return prop.upper() in self.properties(cls)

    def states(self, cls: str) -> frozenset[str]:
        """The states objects of a class can be in (ON, OFF, OPEN, DIRTY, HOT, ...)."""
        facts = self._facts(cls)
        return facts.states if facts else frozenset()

    def default_states(self, cls: str) -> frozenset[str]:
        """The states a fresh object of a class starts in.

        For each pair the class can take, the first of: OFF (not ON), CLOSED (not OPEN),
        CLEAN (not DIRTY), PLUGGED_IN (not PLUGGED_OUT).
        """
        possible = self.states(cls)
        return frozenset(a for a, b in _DEFAULT_OF_PAIR if a in possible and b in possible)

    # -- names -------------------------------------------------------------------------------

    def equivalents(self, name: str) -> list[str]:
        """The scene classes a script name may stand for, the name itself first.

        The list is the name, the classes ``class_name_equivalence`` gives for it, then any
        known class spelled the same but for underscores (``alarm_clock`` -> ``alarmclock``),
        without duplicates. ActivityPrograms names food kinds ``food_<kind>``, so a bare
        kind with no entry of its own uses that one (``fruit`` -> ``food_fruit``); a plural
        the knowledge base does not know stands for its singular (``cups`` -> ``cup``).
        """
        name = normalize_name(name)
        listed = self._equivalences.get(name)
        if listed is None:
            listed = self._equivalences.get(f"food_{name}", [])
        out = [name, *listed, *self._spellings.get(_squash(name), [])]
        if len(out) == 1 and self.resolve(name) is None:
            singular = self._singular(name)
            if singular is not None:
                out += self.equivalents(singular)
        return list(dict.fromkeys(out))

    def _singular(self, name: str) -> str | None:
        """The known class a plural name stands for (``cups``, ``glasses``), or None."""
        for cut in ("es", "s"):
            if name.endswith(cut) and self.resolve(name[:-len(cut)]) is not None:
                return name[:-len(cut)]
        return None

    def script_names(self, cls: str) -> list[str]:
        """The reverse of `equivalents`: the script names a scene class can stand for.

        >>> load_kb().script_names("sofa")
        ['sofa', 'couch', 'love_seat']
        """
        cls = normalize_name(cls)
        out = [cls, *self._script_names.get(cls, []), *self._spellings.get(_squash(cls), [])]
        return list(dict.fromkeys(out))

    # -- placement and size --------------------------------------------------------------------

    def placements(self, cls: str) -> list[Placement]:
        """Where an object of a class may be put, in the knowledge base's order."""
        facts = self._facts(cls)
        return list(facts.placements) if facts else []

    def prefab_size(self, cls: str) -> tuple[float, float, float] | None:
        """Typical size (x, y, z) in metres, Unity frame (y up), of a class's 3D models.

        The per-axis median over the class's prefabs. A class without 3D models of its own
        takes the size of its first equivalent that has some (``television`` -> ``tv``);
        None when none has.
        """
        for name in self.equivalents(cls):
            facts = self._facts(name)
            if facts is not None and facts.size is not None:
                return facts.size
        return None


@lru_cache(maxsize=1)
def load_kb() -> ObjectKB:
    """The built-in object knowledge (loaded once, then cached; it is read-only)."""
    ref = resources.files("homesim.knowledge.builtin") / "objects.json.gz"
    with resources.as_file(ref) as path:
        return ObjectKB.load(path)
