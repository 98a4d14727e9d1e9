"""Render jobs: queued in worker processes, frames fetched one by one, bounded queue."""

from __future__ import annotations

import io
import multiprocessing
import time

import pytest
from fastapi.testclient import TestClient

from homesim.errors import HomesimError
from homesim.limits import MAX_RENDER_PIXEL_FRAMES
from homesim.serve import create_app
from homesim.serve.renders import RenderJobs

FORK = multiprocessing.get_context("fork")  # workers run this module's functions


def coloured_frames(request):
    """One flat frame per step, step i in red level 40 * i."""
    steps = [line for line in request.program.splitlines() if line.startswith("[")]
    for i in range(len(steps)):
        yield i, [[[i * 40, 0, 255]] * request.width] * request.height


def first_frame_then_wait(request):
    yield 0, [[[0, 0, 0]] * request.width] * request.height
    time.sleep(60)


def failing_frames(request):
    raise HomesimError("the home has no floor boxes: rendering needs a home with 3D geometry")
    yield  # a generator, as real sources are


def _client(**jobs) -> TestClient:
    app = create_app(render_jobs=RenderJobs(context=FORK, **jobs))
    return TestClient(app, base_url="http://127.0.0.1", raise_server_exceptions=False)


def _wait(client: TestClient, job: dict, until=("done", "failed", "cancelled")) -> dict:
    deadline = time.monotonic() + 20
    while True:
        status = client.get(job["url"]).json()
        if status["status"] in until or time.monotonic() > deadline:
            return status
        time.sleep(0.05)


def test_render_answers_202_with_a_job_then_one_png_per_key_frame(watch_tv):
    from PIL import Image

    with _client(source=coloured_frames) as client:
        r = client.post("/api/render",
                        json={"program": watch_tv, "home": "scene1", "width": 24, "height": 16})
        assert r.status_code == 202, r.text
        job = r.json()
        assert job["status"] in ("queued", "running") and job["total"] == 5
        status = _wait(client, job)
        assert status["status"] == "done" and status["ready"] == 5
        assert [f["line"] for f in status["frames"]] == [4, 5, 6, 7, 8]
        for frame in status["frames"]:
            png = client.get(frame["url"])
            assert png.status_code == 200 and png.headers["content-type"] == "image/png"
            image = Image.open(io.BytesIO(png.content))
            assert image.size == (24, 16)
            assert image.getpixel((0, 0)) == (frame["index"] * 40, 0, 255)
        assert client.get(f"{job['url']}/frames/5").status_code == 404


def test_render_over_the_pixel_frame_limit_is_422_before_queueing(watch_tv):
    with _client(source=coloured_frames) as client:
        steps = MAX_RENDER_PIXEL_FRAMES // (1280 * 960) + 1
        program = "[Walk] <tv> (1.410)\n" * steps
        r = client.post("/api/render", json={"program": program, "home": "scene1",
                                             "width": 1280, "height": 960})
        assert r.status_code == 422
        assert f"over the limit of {MAX_RENDER_PIXEL_FRAMES:,}" in r.json()["error"]["message"]
        assert client.app.state.renders.jobs == {}


def test_full_render_queue_is_503_with_retry_after(watch_tv):
    with _client(source=first_frame_then_wait, workers=1, queue=1) as client:
        body = {"program": watch_tv, "home": "scene1", "width": 16, "height": 16}
        running, waiting = (client.post("/api/render", json=body) for _ in range(2))
        assert running.status_code == waiting.status_code == 202
        r = client.post("/api/render", json=body)
        assert r.status_code == 503 and int(r.headers["retry-after"]) > 0
        assert "busy" in r.json()["error"]["message"]
        # a frame that is not drawn yet, and cancelling frees the queue
        status = _wait(client, running.json(), until=("running",))
        assert client.get(f"{status['url']}/frames/3").status_code == 409
        assert client.delete(status["url"]).json()["status"] == "cancelled"
        assert client.post("/api/render", json=body).status_code == 202


def test_a_render_job_that_fails_reports_the_error_in_its_status(watch_tv):
    with _client(source=failing_frames) as client:
        job = client.post("/api/render", json={"program": watch_tv, "home": "scene1"}).json()
        status = _wait(client, job)
        assert status["status"] == "failed" and status["ready"] == 0
        assert status["error"]["status"] == 422
        assert "needs a home with 3D geometry" in status["error"]["message"]


def test_a_render_job_over_its_time_is_stopped(watch_tv):
    with _client(source=first_frame_then_wait, timeout=0.5) as client:
        job = client.post("/api/render", json={"program": watch_tv, "home": "scene1",
                                               "width": 16, "height": 16}).json()
        status = _wait(client, job)
        assert status["status"] == "failed" and status["ready"] == 1
        assert "longer than 0.5 s" in status["error"]["message"]
        assert client.get(status["frames"][0]["url"]).status_code == 200


def test_render_grounds_an_ungrounded_program_first(monkeypatch):
    from homesim.serve import programs

    def fake_render(run, *, width, height, seed):
        # grounded to a node of scene1, and run once with its trace for render to animate
        assert str(run.result.program).startswith("[Walk] <tv> (1.")
        assert run.result.trace is not None
        yield 0, [[[0, 0, 0]] * width] * height

    monkeypatch.setattr(programs, "keyframe_renderer", lambda: fake_render)  # forked workers
    with _client() as client:
        job = client.post("/api/render", json={"program": "[Walk] <tv> (1)", "home": "scene1",
                                               "width": 16, "height": 16}).json()
        assert _wait(client, job)["status"] == "done"
        job = client.post("/api/render",
                          json={"program": "[Walk] <garage> (1)", "home": "scene1"}).json()
        status = _wait(client, job)
        assert status["status"] == "failed" and status["error"]["kind"] == "grounding"
        assert status["error"]["status"] == 422


def test_unknown_render_job_is_404(client):
    r = client.get("/api/render/0123456789abcdef")
    assert r.status_code == 404 and "no render job" in r.json()["error"]["message"]


@pytest.mark.render
def test_render_with_the_real_renderer_shows_each_step(watch_tv):
    gl = pytest.importorskip("homesim.render.gl")  # picks MUJOCO_GL before mujoco loads
    if not gl.gl_available():
        pytest.skip(f"no OpenGL context with MUJOCO_GL={gl.BACKEND}")
    import numpy as np
    from PIL import Image

    app = create_app()  # the real worker processes (fork server) and renderer
    with TestClient(app, base_url="http://127.0.0.1") as client:
        job = client.post("/api/render", json={"program": watch_tv, "home": "scene1",
                                               "width": 64, "height": 48}).json()
        status = _wait(client, job)
        assert status["status"] == "done", status
        assert [f["line"] for f in status["frames"]] == [4, 5, 6, 7, 8]
        images = [np.asarray(Image.open(io.BytesIO(client.get(f["url"]).content)))
                  for f in status["frames"]]
        assert all(im.shape == (48, 64, 3) for im in images)
        assert all(im.std() > 5 for im in images)  # a scene, not a blank frame
        assert not np.array_equal(images[0], images[-1])  # the agent moved between steps

        job = client.post("/api/render",
                          json={"program": "[Walk] <tv> (1)", "home": "scene1_trimmed"}).json()
        status = _wait(client, job)
        assert status["status"] == "failed" and status["error"]["status"] == 422
        assert "needs a home with 3D geometry" in status["error"]["message"]


FAKE_MP4 = b"\x00\x00\x00\x18ftypmp42" + bytes(range(256)) * 4


def fake_video(request, path, progress):
    """Three 'frames' with their progress, then a file standing in for the MP4."""
    for done in range(1, 4):
        progress(done, 3)
    with open(path, "wb") as f:
        f.write(FAKE_MP4)
    return 3


def video_then_wait(request, path, progress):
    progress(1, 50)
    time.sleep(60)
    return 50


def failing_video(request, path, progress):
    from homesim.errors import LimitError

    raise LimitError("2400 frames at 320x240 is over the limit of ... frames x pixels per "
                     "video (MAX_RENDER_VIDEO_PIXEL_FRAMES)", "MAX_RENDER_VIDEO_PIXEL_FRAMES")


def test_video_job_answers_202_then_progress_then_an_mp4_with_ranges(watch_tv):
    with _client(video_source=fake_video) as client:
        r = client.post("/api/render/video", json={"program": watch_tv, "home": "scene1",
                                                     "width": 32, "height": 24, "fps": 8})
        assert r.status_code == 202, r.text
        job = r.json()
        assert job["kind"] == "video" and job["video"] is None and job["fps"] == 8
        status = _wait(client, job)
        assert status["status"] == "done", status
        assert (status["ready"], status["total"]) == (3, 3)
        assert status["video"] == f"{job['url']}/video" and status["frames"] == []
        video = client.get(status["video"])
        assert video.status_code == 200 and video.headers["content-type"] == "video/mp4"
        assert video.content == FAKE_MP4
        part = client.get(status["video"], headers={"Range": "bytes=4-11"})
        assert part.status_code == 206 and part.content == b"ftypmp42"
        assert client.get(f"{job['url']}/frames/0").status_code == 404  # a video job
        keyframes = client.post("/api/render", json={"program": watch_tv, "home": "scene1",
                                                     "width": 16, "height": 16}).json()
        r = client.get(f"{keyframes['url']}/video")
        assert r.status_code == 404 and "key frames, not a video" in r.json()["error"]["message"]


def test_a_video_that_is_not_ready_or_failed_is_409_with_the_reason(watch_tv):
    body = {"program": watch_tv, "home": "scene1", "width": 16, "height": 16}
    with _client(video_source=video_then_wait) as client:
        job = _wait(client, client.post("/api/render/video", json=body).json(),
                    until=("running",))
        deadline = time.monotonic() + 20
        while client.get(job["url"]).json()["total"] == 0 and time.monotonic() < deadline:
            time.sleep(0.05)
        r = client.get(f"{job['url']}/video")
        assert r.status_code == 409 and "1 of 50 frames drawn" in r.json()["error"]["message"]
        assert client.delete(job["url"]).json()["status"] == "cancelled"
    with _client(video_source=failing_video) as client:
        job = client.post("/api/render/video", json=body).json()
        status = _wait(client, job)
        assert status["status"] == "failed" and status["error"]["status"] == 422
        assert status["error"]["limit"] == "MAX_RENDER_VIDEO_PIXEL_FRAMES"
        r = client.get(f"{job['url']}/video")
        assert r.status_code == 409 and "MAX_RENDER_VIDEO_PIXEL_FRAMES" in r.text


def test_video_request_fps_is_bounded(watch_tv):
    from homesim.limits import MAX_RENDER_VIDEO_FPS

    with _client(video_source=fake_video) as client:
        r = client.post("/api/render/video", json={
            "program": watch_tv, "home": "scene1", "fps": MAX_RENDER_VIDEO_FPS + 1})
        assert r.status_code == 422 and "fps" in r.json()["error"]["message"]
        assert client.app.state.renders.jobs == {}


@pytest.mark.parametrize(("width", "height"), [(17, 16), (16, 17)])
def test_a_video_of_odd_sides_is_refused_before_it_is_queued(watch_tv, width, height):
    """D15: width 17 was accepted (202) and the job then failed with 422."""
    with _client(source=coloured_frames, video_source=fake_video) as client:
        r = client.post("/api/render/video", json={
            "program": watch_tv, "home": "scene1", "width": width, "height": height})
        assert r.status_code == 422 and "must be even" in r.json()["error"]["message"]
        assert client.app.state.renders.jobs == {}
        r = client.post("/api/render", json={  # key frames are PNGs: any side will do
            "program": watch_tv, "home": "scene1", "width": width, "height": height})
        assert r.status_code == 202


@pytest.mark.render
def test_video_with_the_real_renderer_is_a_playable_mp4(watch_tv, tmp_path):
    gl = pytest.importorskip("homesim.render.gl")
    if not gl.gl_available():
        pytest.skip(f"no OpenGL context with MUJOCO_GL={gl.BACKEND}")
    imageio_ffmpeg = pytest.importorskip("imageio_ffmpeg")  # a decoder other than the writer's

    app = create_app()
    with TestClient(app, base_url="http://127.0.0.1") as client:
        job = client.post("/api/render/video", json={"program": watch_tv, "home": "scene1",
                                                     "width": 64, "height": 48, "fps": 3}).json()
        deadline = time.monotonic() + 60
        status = job
        while status["status"] in ("queued", "running") and time.monotonic() < deadline:
            time.sleep(0.1)
            status = client.get(job["url"]).json()
        assert status["status"] == "done", status
        assert status["ready"] == status["total"] > 10
        path = tmp_path / "v.mp4"
        path.write_bytes(client.get(status["video"]).content)
    reader = imageio_ffmpeg.read_frames(str(path))
    info = next(reader)
    assert info["size"] == (64, 48) and info["fps"] == 3
    assert sum(1 for _ in reader) == status["total"]
