from fastapi.testclient import TestClient

from homesim.serve import create_app


def test_built_editor_is_served_at_root(tmp_path):
    (tmp_path / "index.html").write_text("<!doctype html><title>editor</title>")
    (tmp_path / "app.js").write_text("console.log(1)")
    c = TestClient(create_app(static_dir=tmp_path), base_url="http://localhost")
    assert "<title>editor</title>" in c.get("/").text
    assert c.get("/app.js").text == "console.log(1)"
    assert c.get("/api/homes").status_code == 200  # the API wins over the static mount


def test_without_build_root_says_how_to_build(tmp_path):
    c = TestClient(create_app(static_dir=tmp_path), base_url="http://localhost")
    r = c.get("/")
    assert r.status_code == 200 and "make setup" in r.text
