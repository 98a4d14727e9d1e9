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
