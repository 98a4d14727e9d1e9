"""Convert VirtualHome's object resources into homesim's built-in object knowledge.

Reads the JSON facts in ../shared/data/virtualhome/resources and writes one file,
src/homesim/knowledge/builtin/objects.json.gz, in homesim's own format (see
`homesim.knowledge.objects` for how it is read)::

    {"format": "homesim-objects/1",
     "classes": {class: {"properties": [...], "states": [...],
                         "placements": [[destination, "ON"|"INSIDE", room|null], ...],
                         "size": [x, y, z] | null}},
     "equivalences": {script name: [scene class, ...]}}

Choices made here (each one line in the report this prints):
- properties: ``properties_data.json`` (script names) wins; ``properties_data_all.json``
  adds the classes it lacks (mostly scene spellings such as ``addressbook``).
- states: ``object_states.json`` upper-cased in the graph vocabulary (``plugged`` ->
  PLUGGED_IN, ``unplugged`` -> PLUGGED_OUT); ``grabbed`` is dropped (holding is a relation,
  HOLDS_RH/HOLDS_LH, not a state); the states an affordance implies are added (HAS_SWITCH ->
  ON/OFF, CAN_OPEN -> OPEN/CLOSED, HAS_PLUG -> PLUGGED_IN/PLUGGED_OUT). A scene spelling
  without an entry takes the states of the script name it squashes to (``addressbook`` ->
  ``address_book``).
- placements: ``IN`` becomes INSIDE; the few ``NEARBY`` entries are dropped (not a relation
  objects are put in); the room ``"null"`` becomes null; duplicates are removed, order kept.
- spellings that differ only in underscores (``cutlery_fork``, ``cutleryfork``) share
  facts: a field one lacks is taken from another.
- size: the per-axis median of the sizes (metres, Unity frame, y up) of the class's
  prefabs in ``prefabs_dims.json``, the class's prefabs listed in ``PrefabClass.json``.

Run from the repo root:

    python tools/convert_knowledge.py [../shared/data/virtualhome/resources]
"""

from __future__ import annotations

import gzip
import json
import statistics
import sys
from pathlib import Path

OUT = (Path(__file__).resolve().parents[1] / "src" / "homesim" / "knowledge" / "builtin"
       / "objects.json.gz")
FORMAT = "homesim-objects/1"

_STATE_NAMES = {"plugged": "PLUGGED_IN", "unplugged": "PLUGGED_OUT"}
_DROPPED_STATES = {"grabbed"}
_IMPLIED_STATES = {"HAS_SWITCH": ("ON", "OFF"), "CAN_OPEN": ("OPEN", "CLOSED"),
                   "HAS_PLUG": ("PLUGGED_IN", "PLUGGED_OUT")}
_RELATIONS = {"ON": "ON", "IN": "INSIDE", "INSIDE": "INSIDE"}


def squash(name: str) -> str:
    """A spelling-insensitive key: lower case, no underscores or spaces."""
    return name.lower().replace("_", "").replace(" ", "")


def _load(resources: Path, name: str):
    path = resources / name
    try:
        return json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as e:
        sys.exit(f"{path}: cannot read ({e})")


def _state(name: str) -> str:
    name = name.strip().lower()
    return _STATE_NAMES.get(name, name.upper())


def _share_between_spellings(classes: dict[str, dict]) -> int:
    """Fill a class's empty fields from spellings that differ only in underscores.

    ``cutlery_fork`` has a 3D model but no properties; ``cutleryfork`` has properties but
    no model: both end up with both. The first spelling in sorted order that has a field
    gives it. Returns how many fields were filled.
    """
    spellings: dict[str, list[str]] = {}
    for name in sorted(classes):
        spellings.setdefault(squash(name), []).append(name)
    filled = 0
    for names in spellings.values():
        for key in ("properties", "states", "placements", "size"):
            donor = next((classes[n][key] for n in names if classes[n][key]), None)
            for n in names:
                if donor and not classes[n][key]:
                    classes[n][key] = donor
                    filled += 1
    return filled


def convert(resources: Path) -> tuple[dict, list[str]]:
    """The knowledge file's content and a report of what was converted."""
    props_script: dict[str, list[str]] = _load(resources, "properties_data.json")
    props_all: dict[str, list[str]] = _load(resources, "properties_data_all.json")
    raw_states: dict[str, list[str]] = _load(resources, "object_states.json")
    raw_placing: dict[str, list[dict]] = _load(resources, "object_script_placing.json")
    equivalences: dict[str, list[str]] = _load(resources, "class_name_equivalence.json")
    prefab_classes = _load(resources, "PrefabClass.json")["prefabClasses"]
    dims: dict[str, dict] = _load(resources, "prefabs_dims.json")
    report: list[str] = []

    properties = {k.lower(): sorted(set(v)) for k, v in props_script.items()}
    extra = {k.lower(): sorted(set(v)) for k, v in props_all.items()
             if k.lower() not in properties}
    properties.update(extra)
    report.append(f"properties: {len(props_script)} script classes + {len(extra)} from "
                  f"properties_data_all = {len(properties)}")

    states_by_squash = {squash(k): v for k, v in raw_states.items()}
    dropped_nearby = 0
    placements: dict[str, list[list]] = {}
    for cls, entries in raw_placing.items():
        rows: list[list] = []
        for entry in entries:
            relation = _RELATIONS.get(entry["relation"].upper())
            if relation is None:
                dropped_nearby += 1
                continue
            room = entry.get("room")
            row = [entry["destination"].lower(), relation,
                   None if room in (None, "null", "") else room.lower()]
            if row not in rows:
                rows.append(row)
        placements[cls.lower()] = rows
    report.append(f"placements: {sum(map(len, placements.values()))} for {len(placements)} "
                  f"classes ({dropped_nearby} NEARBY entries dropped)")

    sizes: dict[str, list[float]] = {}
    for entry in prefab_classes:
        found = [dims[p]["size"] for p in entry["prefabs"] if p in dims]
        if found:
            sizes[entry["className"].lower()] = [
                round(statistics.median(axis), 4) for axis in zip(*found, strict=True)]
    report.append(f"sizes: {len(sizes)} of {len(prefab_classes)} prefab classes have "
                  "dimensions")

    names = (set(properties) | set(raw_states) | set(placements) | set(sizes)
             | {d for rows in placements.values() for d, _, _ in rows})
    classes: dict[str, dict] = {}
    for cls in sorted(names):
        props = properties.get(cls, [])
        states = {_state(s) for s in raw_states.get(cls, states_by_squash.get(squash(cls), []))
                  if s.strip().lower() not in _DROPPED_STATES}
        for prop in props:
            states.update(_IMPLIED_STATES.get(prop, ()))
        classes[cls] = {"properties": props, "states": sorted(states),
                        "placements": placements.get(cls, []), "size": sizes.get(cls)}
    filled = _share_between_spellings(classes)
    report.append(f"classes: {len(classes)} in all ({filled} empty fields filled from another "
                  "spelling)")
    equiv = {k.lower(): [v.lower() for v in vs] for k, vs in sorted(equivalences.items())}
    report.append(f"equivalences: {len(equiv)} script names")
    return {"format": FORMAT, "classes": classes, "equivalences": equiv}, report


def main(resources: Path) -> None:
    content, report = convert(resources)
    OUT.parent.mkdir(parents=True, exist_ok=True)
    data = json.dumps(content, sort_keys=True, separators=(",", ":")).encode()
    # mtime=0: the same input gives byte-identical output.
    OUT.write_bytes(gzip.compress(data, mtime=0))
    for line in report:
        print(line)
    print(f"-> {OUT} ({OUT.stat().st_size // 1024} KiB)")


if __name__ == "__main__":
    main(Path(sys.argv[1] if len(sys.argv) > 1 else "../shared/data/virtualhome/resources"))
