"""tools/import_graph.py, the circle check of `make lint`."""

import importlib.util
from pathlib import Path

import pytest

pytest.importorskip("grimp")  # the dev extra (import-linter brings it)

ROOT = Path(__file__).resolve().parents[1]


def _tool():
    spec = importlib.util.spec_from_file_location("import_graph", ROOT / "tools" / "import_graph.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_circles_are_found_with_a_path_through_each():
    tool = _tool()
    edges = {"a": {"b"}, "b": {"a", "c"}, "c": set(), "d": {"e"}, "e": {"f"}, "f": {"d", "c"}}
    assert tool.components(edges) == [["a", "b"], ["d", "e", "f"]]
    assert tool.circle(["d", "e", "f"], edges) == ["d", "e", "f", "d"]
    assert tool.components({"a": {"b"}, "b": {"c"}, "c": set()}) == []


def test_a_known_package_hides_only_its_own_circles(monkeypatch, capsys):
    tool = _tool()
    edges = {"p.x.a": {"p.x.b"}, "p.x.b": {"p.x.a"}, "p.y": {"p.z"}, "p.z": {"p.y"}}
    monkeypatch.setattr(tool, "import_edges", lambda package: edges)
    assert tool.main(["p"]) == 1
    assert tool.main(["p", "--known", "p.x"]) == 1  # p.y <-> p.z is not inside p.x
    assert tool.main(["p", "--known", "p.x", "--known", "p.y"]) == 1  # p.z is outside p.y
    edges.pop("p.z")
    edges["p.y"] = set()
    assert tool.main(["p", "--known", "p.x"]) == 0
    capsys.readouterr()
    assert tool.main(["p", "--known", "p.x", "--known", "p.q"]) == 0
    assert "--known p.q: it has no circle any more" in capsys.readouterr().out


def test_homesim_has_no_circle_between_its_files():
    edges = _tool().import_edges("homesim")
    assert "homesim.sim.execute" in edges and "homesim.world.classes" in edges["homesim.sim.execute"]
    assert "homesim.learn.rerank.base" in edges["homesim.learn.rerank.insertion"]  # learn counts
    assert _tool().components(edges) == []
