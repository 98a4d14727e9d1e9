"""The Host check: loopback names by default, others refused (DNS rebinding)."""

import pytest
from fastapi.testclient import TestClient

from homesim.serve import create_app


@pytest.mark.parametrize("host", ["localhost:8000", "127.0.0.1:8000", "[::1]:8000",
                                  "LOCALHOST", "127.0.0.1"])
def test_loopback_names_are_served(client, host):
    r = client.get("/api/homes", headers={"host": host})
    assert r.status_code == 200, r.text


@pytest.mark.parametrize("host", ["evil.example", "evil.example:8000", "localhost.evil.example",
                                  "127.0.0.2", "[::2]:8000"])
def test_other_names_are_refused_with_the_fix(client, host):
    r = client.get("/api/homes", headers={"host": host})
    assert r.status_code == 400
    message = r.json()["error"]["message"]
    assert message.startswith(f"Host '{host.split(':8000')[0].lower()}' is not served here")
    assert "--allowed-host" in message


def test_configured_names_and_any(watch_tv):
    lan = TestClient(create_app(allowed_hosts=["homesim.lan"]), base_url="http://homesim.lan")
    assert lan.post("/api/validate", json={"program": watch_tv}).status_code == 200
    assert lan.get("/api/homes", headers={"host": "localhost"}).status_code == 400
    anyone = TestClient(create_app(allowed_hosts=["*"]), base_url="http://evil.example")
    assert anyone.get("/api/homes").status_code == 200


@pytest.mark.parametrize("host", ["[::1]evil.com", "[::1]:8000evil", "localhost:evil",
                                  "localhost:8000:1", "[::1]]", "[::1", "localhost:"])
def test_a_loopback_name_with_something_after_it_is_refused(client, host):
    """D16: ``Host: [::1]evil.com`` was served (the name was cut at the bracket)."""
    assert client.get("/api/homes", headers={"host": host}).status_code == 400
