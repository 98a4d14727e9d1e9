"""Large programs are answered by a worker process, the same as small ones in-process."""

from __future__ import annotations

import asyncio
import time

import pytest

from homesim.limits import INLINE_PROGRAM_CHARS
from homesim.serve.pool import ProgramPool
from homesim.serve.programs import validate
from homesim.serve.schemas import ProgramRequest
from homesim.serve.workers import answer_in_worker


def test_a_large_program_is_answered_by_a_worker_like_a_small_one(client):
    program = "[Walk] <tv> (1.410)\n" * (INLINE_PROGRAM_CHARS // 20 + 1)
    assert len(program) > INLINE_PROGRAM_CHARS
    r = client.post("/api/validate", json={"program": program, "home": "scene1"})
    assert r.status_code == 200
    assert r.json() == validate(ProgramRequest(program=program, home="scene1"))
    bad = client.post("/api/execute", json={"program": program + "[Wlak] <tv> (1)",
                                            "home": "scene1"})
    assert bad.status_code == 422 and "unknown action 'Wlak'" in bad.json()["error"]["message"]
    assert bad.json()["error"]["line"] == program.count("\n") + 1


def test_errors_in_a_worker_answer_as_the_app_does():
    status, body = answer_in_worker(validate, ProgramRequest(program="[Wlak] <tv> (1)"))
    assert status == 422 and b"unknown action 'Wlak'" in body


def test_a_full_program_pool_is_503_with_retry_after():
    from homesim.serve.errors import ApiError

    async def three_at_once() -> list:
        pool = ProgramPool(workers=1, queue=1)
        try:
            return await asyncio.gather(*(pool.answer(time.sleep, 0.5) for _ in range(3)),
                                        return_exceptions=True)
        finally:
            pool.close()

    answers = asyncio.run(three_at_once())
    assert [getattr(a, "status_code", None) for a in answers[:2]] == [200, 200]
    assert isinstance(answers[2], ApiError) and answers[2].status == 503
    assert answers[2].headers["Retry-After"] == "2"


@pytest.mark.parametrize("route", ["validate", "execute"])
def test_a_256_kib_one_line_program_gets_a_short_422(client, route):
    r = client.post(f"/api/{route}", json={"program": "[Walk] <tv> (1) " * 16000,
                                           "home": "scene1"})
    assert r.status_code == 422 and len(r.content) < 2000
