"""A data set read for the video tasks: every episode reduced once (`cache`) and written
into one frame store (`store`), with the split its folders declare (`splits`).

`--data` is a plan folder (`homesim dataset generate --plan`: its parts are its split), or
data set folders made without a plan (several separated by commas), split by
`splits.LEGACY`. A folder whose generation is still running is read as far as its
finished shards go.
"""

from __future__ import annotations

from pathlib import Path

from homesim.dataset.layout import Layout
from homesim.dataset.plan import read_plan
from homesim.errors import HomesimError
from homesim.learn.data import Example
from homesim.learn.video.cache import VideoFormat, cache_file, episode_rows, fill_cache
from homesim.learn.video.splits import LEGACY, Split, legacy_part
from homesim.learn.video.store import FrameStore, StoredEpisode, build_store, store_name
from homesim.program.parse import parse_program


def _folder_items(folder: Path, fmt: VideoFormat, cache: Path, workers: int
                  ) -> list[tuple[dict, Path]]:
    """(manifest row, reduced episode file) of the folder's finished episodes, reduced
    first where not yet cached."""
    if not (folder / "dataset.json").is_file():
        raise HomesimError(f"{folder}: not a data set folder (run 'homesim dataset generate')")
    layout = Layout(folder)
    shards = [(layout.shards / s["name"], s["rows"]) for s in layout.finished_shards()]
    fill_cache([(path, episode_rows(rows)) for path, rows in shards], fmt, cache, workers)
    return [(r, cache_file(cache, r["sha256"], fmt)) for _, rows in shards for r in rows
            if r["status"] == "ok"]


def read_store(data: str, fmt: VideoFormat, cache: Path, workers: int = 1
               ) -> tuple[FrameStore, Split]:
    """The frame store of `data` and its split (see the module)."""
    folders = [Path(p) for p in data.split(",")]
    plan = read_plan(folders[0]) if len(folders) == 1 else None
    items: list[tuple[str, str, Path]] = []
    if plan is not None:
        split = Split({p.name: p.role for p in plan.plan.parts}, plan.plan.rows)
        for part in plan.plan.parts:
            for row, path in _folder_items(plan.folder(part.name), fmt, cache, workers):
                items.append((part.name, f"{part.name}/{row['key']}", path))
    else:
        split = LEGACY
        for folder in folders:
            for row, path in _folder_items(folder, fmt, cache, workers):
                key = f"{folder.name}/{row['key']}" if len(folders) > 1 else row["key"]
                items.append((legacy_part(key, row["home"], row["agent"]), key, path))
    if not items:
        raise HomesimError(f"{data}: no finished shards (run 'homesim dataset generate')")
    name = store_name([(part, key, path.name) for part, key, path in items], fmt.tag)
    return build_store(cache / "stores" / name, items), split


def example(ep: StoredEpisode) -> Example:
    """The episode's program as a learning example (its key is the id)."""
    return Example(ep.key, parse_program(ep.program), source=ep.part, home=ep.home)
