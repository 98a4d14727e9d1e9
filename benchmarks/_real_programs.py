"""The real programs as the benchmarks run them: ungrounded text (class + per-class counter)."""

from __future__ import annotations


def ungrounded_texts(limit: int = 0) -> list[str]:
    """The fetched real programs (the first `limit` when > 0), node ids taken out."""
    from homesim.ground import unground
    from homesim.knowledge import real_programs

    programs = list(real_programs())
    if limit:
        programs = programs[:limit]
    return [str(unground(rp.program)) for rp in programs]
