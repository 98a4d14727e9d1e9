import pytest

from homesim.knowledge import fetch
from homesim.learn.rerank import program_writer as writer


@pytest.fixture
def small(small_writer, monkeypatch):
    monkeypatch.setattr(writer, "real_writer", lambda: small_writer)
    return small_writer


def test_write_answers_the_program_and_its_run(client, small):
    r = client.post("/api/write", json={"description": "Turn on the TV and watch it.",
                                        "title": "Watch TV", "home": "scene3"})
    assert r.status_code == 200, r.text
    data = r.json()
    assert data["program"].startswith("Watch TV\nTurn on the TV and watch it.\n\n[")
    assert data["home"] == "scene3" and data["title_given"] and data["executable"]
    assert [s["line"] for s in data["run"]["steps"]] == list(range(4, 4 + len(data["steps"])))
    guessed = client.post("/api/write", json={"description": "Turn on the TV and watch it.",
                                              "title": ""}).json()
    assert guessed["title"] == "Watch TV" and not guessed["title_given"]


@pytest.mark.parametrize(("body", "status", "words"), [
    ({"description": " "}, 422, "description: empty"),
    ({"description": "x" * 2001}, 422, "(MAX_DESCRIPTION_CHARS)"),
    ({"description": "tv", "title": "t" * 2001}, 422, "title: 2001 characters"),
    ({"description": "tv", "home": "nowhere"}, 404, "unknown home 'nowhere'"),
    ({"title": "Watch TV"}, 422, "description: Field required"),
])
def test_write_refuses_bad_requests_with_one_message(client, small, body, status, words):
    r = client.post("/api/write", json=body)
    assert r.status_code == status and words in r.json()["error"]["message"]


def test_write_without_the_real_programs_says_how_to_get_them(client, monkeypatch):
    monkeypatch.setattr(fetch, "is_fetched", lambda root=None: False)
    r = client.post("/api/write", json={"description": "Turn on the TV."})
    assert r.status_code == 503 and "homesim data fetch" in r.json()["error"]["message"]
