import sys

import pytest

from homesim.cli import serve as serve_cli
from homesim.cli.main import main


def test_serve_help_mentions_loopback_default(capsys):
    assert main(["serve", "--help"]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "127.0.0.1" in out and "--port" in out


def test_serve_runs_uvicorn_on_loopback(monkeypatch, capsys):
    calls = {}
    uvicorn = pytest.importorskip("uvicorn")
    monkeypatch.setattr(uvicorn, "run", lambda app, **kw: calls.update(kw, app=app))
    assert main(["serve", "--port", "8123"]) == 0
    assert calls["host"] == "127.0.0.1" and calls["port"] == 8123
    assert "http://127.0.0.1:8123/" in capsys.readouterr().out


def test_serve_without_extra_says_how_to_install(monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "uvicorn", None)  # import uvicorn -> ModuleNotFoundError
    assert main(["serve"]) == 2
    err = " ".join(capsys.readouterr().err.split())
    assert "needs the serve extra" in err and "with its 'serve' extra" in err


def test_bad_port_is_one_line(capsys):
    assert main(["serve", "--port", "70000"]) == 2
    assert "--port 70000: not a TCP port" in capsys.readouterr().err


def test_busy_port_is_one_line(monkeypatch, capsys):
    uvicorn = pytest.importorskip("uvicorn")

    def busy(app, **kw):
        raise OSError(98, "Address already in use")

    monkeypatch.setattr(uvicorn, "run", busy)
    assert main(["serve", "--port", "8124"]) == 2
    assert "cannot listen on 127.0.0.1:8124 (Address already in use)" in capsys.readouterr().err
    assert serve_cli.LOOPBACK == "127.0.0.1"
