import re
from pathlib import Path

from homesim import limits

DOC = Path(__file__).resolve().parents[1] / "docs" / "limits.md"


def test_every_limit_is_documented_with_its_value_in_one_place():
    names = [n for n in vars(limits) if re.fullmatch(r"[A-Z][A-Z0-9_]+", n)]
    text = DOC.read_text()
    assert "MAX_STEPS" in names and "RENDER_QUEUE" in names
    missing = [n for n in names if f"`{n}`" not in text]
    assert not missing, f"docs/limits.md does not list {missing}"


def test_the_api_reads_its_body_limit_from_here():
    from homesim.serve.limits import MAX_BODY_BYTES

    assert MAX_BODY_BYTES == limits.MAX_REQUEST_BYTES
