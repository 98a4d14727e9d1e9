from fastapi import FastAPI
from fastapi.testclient import TestClient

from homesim.errors import DataError
from homesim.serve.errors import install_error_handlers


def _app() -> TestClient:
    app = FastAPI()
    install_error_handlers(app)

    @app.get("/data")
    def data():
        raise DataError("programs/1.txt: not UTF-8")

    @app.get("/bug")
    def bug():
        raise KeyError("oops")

    @app.get("/number/{n}")
    def number(n: int):
        return {"n": n}

    return TestClient(app, raise_server_exceptions=False)


def test_homesim_error_is_one_line_422():
    r = _app().get("/data")
    assert r.status_code == 422
    assert r.json() == {"error": {"kind": "DataError", "message": "programs/1.txt: not UTF-8"}}


def test_bug_is_500_with_one_line_and_no_traceback():
    r = _app().get("/bug")
    assert r.status_code == 500
    message = r.json()["error"]["message"]
    assert message == "internal error: KeyError: 'oops' (please report it)"


def test_schema_error_names_the_field():
    r = _app().get("/number/abc")
    assert r.status_code == 422
    assert r.json()["error"]["message"].startswith("path.n: Input should be a valid integer")


def test_a_lone_surrogate_in_a_request_is_answered_not_500(client):
    # JSON may escape a lone surrogate; Python decodes it, UTF-8 cannot encode it.
    body = '{"program": "Title \\ud800\\nabout\\n\\n[Walk] <tv> (1.410)", "home": "scene1"}'
    for route in ("validate", "execute", "render"):
        r = client.post(f"/api/{route}", content=body,
                        headers={"content-type": "application/json"})
        assert r.status_code == 422 and "lone surrogate" in r.json()["error"]["message"]
    r = client.post("/api/validate", content='{"program": "[Walk] <tv> (1)", "home": "\\udfff"}',
                    headers={"content-type": "application/json"})
    assert r.status_code == 404


def test_every_json_answer_serialises_lone_surrogates_as_replacement_characters():
    from homesim.serve.errors import SafeJSONResponse, error_response

    assert SafeJSONResponse({"text": "a\ud800b"}).body == '{"text":"a\ufffdb"}'.encode()
    assert b"\xef\xbf\xbd" in error_response(422, "program", "line 1: W\udfff").body


def test_long_error_texts_are_clipped(client):
    from homesim.limits import MAX_MESSAGE_CHARS
    from homesim.serve.errors import error_response

    r = client.post("/api/validate", json={"program": "[Walk] <tv> (1) " * 4000})
    assert r.status_code == 422 and len(r.content) < 4 * MAX_MESSAGE_CHARS
    body = error_response(422, "program", "x" * 10_000, text="y" * 10_000).body.decode()
    assert body == ('{"error":{"kind":"program","message":"' + "x" * (MAX_MESSAGE_CHARS - 1)
                    + '…","text":"' + "y" * (MAX_MESSAGE_CHARS - 1) + '…"}}')


def _exchange(sock, request: bytes) -> bytes:
    """Send one request on a socket and read one whole answer (Content-Length framed)."""
    sock.sendall(request)
    data = b""
    while b"\r\n\r\n" not in data:
        chunk = sock.recv(65536)
        if not chunk:
            return data
        data += chunk
    head, _, body = data.partition(b"\r\n\r\n")
    length = next(int(line.split(b":")[1]) for line in head.split(b"\r\n")
                  if line.lower().startswith(b"content-length:"))
    while len(body) < length:
        chunk = sock.recv(65536)
        if not chunk:
            break
        body += chunk
    return head + b"\r\n\r\n" + body


def test_after_a_500_the_same_connection_answers_the_next_request(tmp_path):
    import socket
    from urllib.parse import urlsplit

    from homesim.serve import create_app
    from tests.serve.conftest import start_server

    app = create_app(static_dir=tmp_path)

    @app.get("/api/bug")
    def bug():
        raise KeyError("oops")

    url, server, thread = start_server(app=app)
    try:
        address = urlsplit(url)
        with socket.create_connection((address.hostname, address.port), timeout=10) as sock:
            first = _exchange(sock, b"GET /api/bug HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
            assert first.startswith(b"HTTP/1.1 500") and b"KeyError: 'oops'" in first
            second = _exchange(sock, b"GET /api/homes HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
            assert second.startswith(b"HTTP/1.1 200"), second[:200]
    finally:
        server.should_exit = True
        thread.join(timeout=10)
