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


@pytest.mark.parametrize("body", [
    b'{"program": ' + b"[" * 5000 + b"]" * 5000 + b"}",  # deeper than json.loads recurses
    b"[" * 100 + b"]" * 100,
    b'{"a":' * 40 + b"1" + b"}" * 40,
])
def test_json_nested_too_deep_is_422(client, body):
    from homesim.limits import MAX_JSON_DEPTH

    r = client.post("/api/validate", content=body, headers={"content-type": "application/json"})
    assert r.status_code == 422
    assert r.json()["error"]["message"] == (f"request body is nested deeper than {MAX_JSON_DEPTH} "
                                            "levels of JSON arrays and objects")


def test_brackets_inside_strings_are_not_nesting(client):
    program = "[Walk] <tv> (1.410)\n" * 200 + '\\"[[[[' * 50
    r = client.post("/api/validate", json={"program": program})
    assert r.status_code in (200, 422) and "nested deeper" not in r.text


def trickle(url: str, start: bytes, limit_s: float = 5.0) -> tuple[bytes, float]:
    """Send `start`, then one byte every 0.05 s until the server answers and closes the
    connection; the answer and the seconds it took."""
    import select
    import socket
    import time
    from urllib.parse import urlsplit

    address = urlsplit(url)
    answer = b""
    with socket.create_connection((address.hostname, address.port), timeout=limit_s) as sock:
        sock.sendall(start)
        t0 = time.monotonic()
        while time.monotonic() - t0 < limit_s:
            if select.select([sock], [], [], 0.05)[0]:
                try:
                    chunk = sock.recv(65536)
                except ConnectionResetError:
                    break
                if not chunk:
                    break
                answer += chunk
                continue
            try:
                sock.sendall(b" ")
            except (BrokenPipeError, ConnectionResetError):
                break
        return answer, time.monotonic() - t0


def test_a_body_trickled_slower_than_its_deadline_gets_408_and_is_closed(tmp_path):
    from homesim.serve import create_app
    from tests.serve.conftest import start_server

    url, server, thread = start_server(app=create_app(static_dir=tmp_path, body_timeout=0.5))
    try:
        answer, seconds = trickle(url, b"POST /api/validate HTTP/1.1\r\nHost: 127.0.0.1\r\n"
                                  b"content-type: application/json\r\n"
                                  b"content-length: 100000\r\n\r\n{")
        assert seconds < 3
        assert answer.startswith(b"HTTP/1.1 408") and b"not received within 0.5 s" in answer
    finally:
        server.should_exit = True
        thread.join(timeout=10)


def test_large_bodies_are_let_in_a_few_at_a_time_and_the_rest_refused():
    import asyncio

    from homesim.serve.limits import LargeBodyGate

    inside = []

    async def slow_app(scope, receive, send):
        inside.append(scope["path"])
        await asyncio.sleep(0.2)
        await send({"type": "http.response.start", "status": 200, "headers": []})
        await send({"type": "http.response.body", "body": b"ok"})

    gate = LargeBodyGate(slow_app, threshold=100, at_once=1, waiting=1)

    async def call(path: str, length: int) -> tuple[int, dict, float]:
        scope = {"type": "http", "method": "POST", "path": path,
                 "headers": [(b"content-length", str(length).encode())]}
        sent = []

        async def receive():
            return {"type": "http.request", "body": b" " * length, "more_body": False}

        async def send(message):
            sent.append(message)

        t0 = asyncio.get_running_loop().time()
        await gate(scope, receive, send)
        headers = {k.decode(): v.decode() for k, v in sent[0].get("headers", [])}
        return sent[0]["status"], headers, asyncio.get_running_loop().time() - t0

    async def scenario():
        large = [asyncio.create_task(call(f"/large{i}", 1000)) for i in range(3)]
        await asyncio.sleep(0.05)
        small = await call("/small", 10)
        return small, await asyncio.gather(*large)

    small, large = asyncio.run(scenario())
    assert small[0] == 200 and small[2] < 0.3  # not queued behind the large ones
    assert [status for status, _, _ in large] == [200, 200, 503]
    assert large[2][1]["retry-after"] == "2" and large[2][2] < 0.1
    assert large[1][2] > 0.35  # waited for the first
    assert inside == ["/large0", "/small", "/large1"]
