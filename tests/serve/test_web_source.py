"""The editor's source keeps no per-action facts: they come from ``/api/actions``."""

from __future__ import annotations

import re
from pathlib import Path

from homesim.program import ACTIONS

WEB_SRC = Path(__file__).resolve().parents[2] / "web" / "src"


def test_no_action_key_is_spelled_in_the_editor_source():
    # A key or alias in the TypeScript means a table that duplicates the catalog
    # (connector words, aliases, suitable objects), which drifts when a row changes.
    names = sorted(set(ACTIONS) | {alias for a in ACTIONS.values() for alias in a.aliases})
    for path in sorted(WEB_SRC.glob("*.ts")):
        text = path.read_text(encoding="utf-8")
        found = [k for k in names if re.search(rf"\b{k}\b", text)]
        assert not found, f"{path.name} names catalog actions {found}: read them from the API"
