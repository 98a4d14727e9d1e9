"""Oversized bodies get 413 (declared or streamed), and the server keeps answering."""

import httpx
import pytest

from homesim.serve.limits import MAX_BODY_BYTES


def _big_program() -> str:
    return "[Walk] <tv> (1.410)\n" * (MAX_BODY_BYTES // 20 + 10)


def test_oversized_body_is_413_with_the_limit(client):
    r = client.post("/api/execute", json={"program": _big_program(), "home": "scene1"})
    assert r.status_code == 413
    message = r.json()["error"]["message"]
    assert "over the 256 KiB limit" in message and message.startswith("request body is ")


def test_body_at_the_limit_is_read(client):
    body = b'{"program": "[Walk] <tv> (1.410)", "home": "scene1"}'
    body += b" " * (MAX_BODY_BYTES - len(body))
    r = client.post("/api/execute", content=body, headers={"content-type": "application/json"})
    assert r.status_code == 200 and r.json()["executable"] is True


def test_bad_content_length_is_400(client):
    r = client.post("/api/validate", content=b"{}",
                    headers={"content-type": "application/json", "content-length": "x"})
    assert r.status_code == 400 and "Content-Length" in r.json()["error"]["message"]


def _chunks(total: int, size: int = 16 * 1024):
    sent = 0
    while sent < total:
        yield b" " * min(size, total - sent)
        sent += size


@pytest.mark.parametrize(
    ("send", "status", "fragment"),
    [
        (lambda c: c.get("/api/homes/scene7/objects"), 404, "unknown home 'scene7'"),
        (lambda c: c.post("/api/execute", json={"program": "[Wlak] <tv> (1)", "home": "scene1"}),
         422, "unknown action 'Wlak'"),
        (lambda c: c.post("/api/execute", content=b"{not json",
                          headers={"content-type": "application/json"}),
         422, "request body is not valid JSON"),
        (lambda c: c.post("/api/execute", json={"program": _big_program(), "home": "scene1"}),
         413, "over the 256 KiB limit"),
        # Chunked: no Content-Length, counted while it streams in.
        (lambda c: c.post("/api/execute", content=_chunks(2 * MAX_BODY_BYTES),
                          headers={"content-type": "application/json"}),
         413, "request body is at least"),
        (lambda c: c.delete("/api/execute"), 405, "DELETE is not allowed on /api/execute"),
        (lambda c: c.get("/api/nothing"), 404, "no such page or API route: /api/nothing"),
    ],
)
def test_live_server_answers_bad_requests_and_stays_up(live_server, watch_tv, send, status,
                                                       fragment):
    with httpx.Client(base_url=live_server, timeout=20) as c:
        r = send(c)
        assert r.status_code == status
        assert fragment in r.json()["error"]["message"]
        ok = c.post("/api/execute", json={"program": watch_tv, "home": "scene1"})
        assert ok.status_code == 200 and ok.json()["executable"] is True
