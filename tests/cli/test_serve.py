import sys

import pytest

from homesim.cli import serve as serve_cli
from homesim.cli.main import main


def test_serve_help_mentions_loopback_default(capsys):
    assert main(["serve", "--help"]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "127.0.0.1" in out and "--port" in out


def _captured_config(monkeypatch) -> dict:
    uvicorn = pytest.importorskip("uvicorn")
    seen: dict = {}
    monkeypatch.setattr(uvicorn.Server, "run", lambda self: seen.update(config=self.config))
    return seen


def test_serve_runs_uvicorn_on_loopback(monkeypatch, capsys):
    seen = _captured_config(monkeypatch)
    assert main(["serve", "--port", "8123"]) == 0
    config = seen["config"]
    assert config.host == "127.0.0.1" and config.port == 8123
    assert "http://127.0.0.1:8123/" in capsys.readouterr().out


def test_serve_has_deadlines_for_slow_clients_and_for_stopping(monkeypatch):
    from homesim.limits import HEADER_TIMEOUT_S, KEEP_ALIVE_S, SHUTDOWN_GRACE_S

    seen = _captured_config(monkeypatch)
    assert main(["serve"]) == 0
    config = seen["config"]
    assert config.timeout_keep_alive == KEEP_ALIVE_S
    assert config.timeout_graceful_shutdown == SHUTDOWN_GRACE_S <= 5
    assert config.http.header_timeout == HEADER_TIMEOUT_S


def _hosts(config) -> frozenset:
    from homesim.serve.hosts import HostCheck

    layer = next(m for m in config.app.user_middleware if m.cls is HostCheck)
    return HostCheck(None, **layer.kwargs).allowed


def test_serve_answers_loopback_names_by_default_and_allowed_hosts(monkeypatch):
    seen = _captured_config(monkeypatch)
    assert main(["serve"]) == 0
    assert _hosts(seen["config"]) == {"localhost", "127.0.0.1", "[::1]"}
    assert main(["serve", "--host", "0.0.0.0", "--allowed-host", "homesim.lan",
                 "--allowed-host", "10.0.0.2"]) == 0
    assert _hosts(seen["config"]) == {"homesim.lan", "10.0.0.2"}
    assert main(["serve", "--host", "192.168.1.5"]) == 0
    assert "192.168.1.5" in _hosts(seen["config"])


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

    def busy(self):
        raise OSError(98, "Address already in use")

    monkeypatch.setattr(uvicorn.Server, "run", busy)
    assert main(["serve", "--port", "8124"]) == 2
    assert "cannot listen on 127.0.0.1:8124 (Address already in use)" in capsys.readouterr().err
    assert serve_cli.LOOPBACK == "127.0.0.1"
