"""Render jobs: ``POST /api/render`` (key frames) or ``POST /api/render/video`` (the whole
program as one MP4) queues one; the client then fetches its frames or video by URL.

Rendering is CPU-heavy and slow (MuJoCo), so it never runs in the server process:

- ``POST /api/render`` checks the request (program, home, frames x pixels; see
  `programs.render_plan`), queues a job and answers 202 with its id and URLs; 503 with
  ``Retry-After`` when `RENDER_WORKERS` jobs run and `RENDER_QUEUE` more wait.
- Each job runs in its own worker process (niced), which writes one PNG per key frame
  into the job's folder as soon as it is drawn, so memory holds one frame at a time.
  A job running longer than `RENDER_TIMEOUT_S` is killed.
- A video job's worker writes the MP4 frame by frame (memory holds one frame) and its
  progress (frames drawn of the total) as it goes; the file appears when it is complete.
- ``GET /api/render/{id}`` tells the job's status and the frames ready so far (of a
  video: frames drawn); ``GET /api/render/{id}/frames/{index}`` is one PNG,
  ``GET /api/render/{id}/video`` the MP4; ``DELETE`` cancels a job.
- Finished jobs are kept `RENDER_KEEP_S` seconds, the newest `RENDER_KEEP_JOBS` of them.
"""

from __future__ import annotations

import asyncio
import atexit
import json
import math
import os
import secrets
import shutil
import signal
import tempfile
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from fastapi import APIRouter, Request
from fastapi.responses import FileResponse, Response
from starlette.concurrency import run_in_threadpool

from homesim.limits import (
    RENDER_KEEP_JOBS,
    RENDER_KEEP_S,
    RENDER_QUEUE,
    RENDER_TIMEOUT_S,
    RENDER_WORKERS,
    WORKER_MEMORY_BYTES,
)
from homesim.serve import programs
from homesim.serve.errors import ApiError, SafeJSONResponse, error_of
from homesim.serve.images import encode_png
from homesim.serve.pool import answer_or_gone
from homesim.serve.programs import is_heavy, render_frames, render_plan, render_video_file
from homesim.serve.schemas import RenderRequest, VideoRequest
from homesim.serve.workers import (
    ProcessContext,
    busy,
    limit_memory,
    lower_priority,
    worker_context,
)

router = APIRouter(prefix="/api", tags=["programs"])

FrameSource = Callable[[Any], Iterable[tuple[int, Any]]]
"""``source(request) -> (step index, RGB frame) ...``, called in the worker process."""

VideoSource = Callable[[Any, str, Callable[[int, int], None]], int]
"""``source(request, mp4_path, progress) -> frames``, called in the worker process;
``progress(done, total)`` after each frame."""

_POLL_S = 0.05
VIDEO = "video.mp4"
PROGRESS = "progress.json"
_PROGRESS_EVERY_S = 0.2


def frame_name(index: int) -> str:
    return f"{index:05d}.png"


def _write_atomically(path: Path, data: bytes) -> None:
    """Write to a side file, then rename: readers never see half a file."""
    part = path.with_name(path.name + ".part")
    part.write_bytes(data)
    os.replace(part, path)


def limit_worker(timeout: float | None) -> None:
    """A render worker's own limits: lower priority, `WORKER_MEMORY_BYTES`, and an alarm
    that ends it a little after `timeout` even if the server that should stop it is gone
    (SIGALRM's default action: a handler a forked worker inherits, e.g. a test runner's
    time limit, would turn the alarm into an exception its job may catch)."""
    lower_priority()
    limit_memory(WORKER_MEMORY_BYTES)
    if timeout:
        signal.signal(signal.SIGALRM, signal.SIG_DFL)
        signal.alarm(math.ceil(timeout) + 2)


def run_job(source: FrameSource, request: Any, out_dir: str, timeout: float | None = None
            ) -> None:
    """The body of a render worker process: PNGs as frames come, then ``done.json`` or
    ``error.json`` (status and error body, as the API answers them)."""
    out = Path(out_dir)
    limit_worker(timeout)
    try:
        count = 0
        for index, rgb in source(request):
            _write_atomically(out / frame_name(index), encode_png(rgb))
            count += 1
        _write_atomically(out / "done.json", json.dumps({"frames": count}).encode())
    except Exception as e:  # reported to the client through the job's status
        _fail(out, e)


def _fail(out: Path, e: Exception) -> None:
    status, body = error_of(e)
    _write_atomically(out / "error.json", json.dumps({"status": status, **body}).encode())


class _ProgressFile:
    """``progress(done, total)`` into a JSON file, at most every `_PROGRESS_EVERY_S`
    (and always for the last frame)."""

    def __init__(self, path: Path):
        self.path, self.last = path, 0.0

    def __call__(self, done: int, total: int) -> None:
        now = time.monotonic()
        if done == total or now - self.last >= _PROGRESS_EVERY_S:
            self.last = now
            _write_atomically(self.path, json.dumps({"done": done, "total": total}).encode())


def run_video_job(source: VideoSource, request: Any, out_dir: str,
                  timeout: float | None = None) -> None:
    """The body of a video worker process: the MP4 (complete, or not there at all) and
    ``progress.json`` as it goes, then ``done.json`` or ``error.json``."""
    out = Path(out_dir)
    limit_worker(timeout)
    try:
        part = out / "video.part.mp4"  # the extension tells ffmpeg the container
        frames = source(request, str(part), _ProgressFile(out / PROGRESS))
        os.replace(part, out / VIDEO)
        _write_atomically(out / "done.json", json.dumps({"frames": frames}).encode())
    except Exception as e:  # reported to the client through the job's status
        _fail(out, e)


@dataclass
class Job:
    """One render request: its folder, the line of each step, its kind (``keyframes``
    or ``video``) and its state."""

    id: str
    folder: Path
    request: RenderRequest
    lines: list[int]
    kind: str = "keyframes"
    state: str = "queued"  # queued, running, done, failed, cancelled
    created: float = field(default_factory=time.monotonic)
    started: float | None = None
    finished: float | None = None
    error: dict[str, Any] | None = None
    process: Any = None

    @property
    def total(self) -> int:
        return len(self.lines)

    def ready(self) -> int:
        """Frames written so far (frames are written in step order)."""
        if self.state == "queued" or not self.folder.is_dir():
            return 0
        return sum(1 for name in os.listdir(self.folder) if name.endswith(".png"))

    def progress(self) -> tuple[int, int]:
        """A video job's (frames drawn, frames in all); the total is 0 until known."""
        try:
            data = json.loads((self.folder / PROGRESS).read_text(encoding="utf-8"))
        except (OSError, ValueError):
            return 0, 0
        return int(data["done"]), int(data["total"])

    def to_json(self) -> dict[str, Any]:
        url = f"/api/render/{self.id}"
        answer = {
            "id": self.id, "url": url, "kind": self.kind, "status": self.state,
            "home": self.request.home, "width": self.request.width,
            "height": self.request.height, "error": self.error,
        }
        if self.kind == "video":
            done, total = self.progress()
            return {**answer, "fps": getattr(self.request, "fps", None), "total": total,
                    "ready": done, "frames": [],
                    "video": f"{url}/video" if self.state == "done" else None}
        ready = self.ready()
        return {**answer, "total": self.total, "ready": ready, "video": None,
                "frames": [{"index": i, "line": self.lines[i], "url": f"{url}/frames/{i}"}
                           for i in range(ready)]}


class RenderJobs:
    """The queue and worker processes of render jobs (one process per running job).

    `source` draws the key frames in the worker, `video_source` writes a video; `context`
    starts workers (default: the fork server of `homesim.serve.workers`; tests pass
    ``fork`` to use local functions).
    """

    def __init__(self, source: FrameSource = render_frames, workers: int = RENDER_WORKERS,
                 queue: int = RENDER_QUEUE, timeout: float = RENDER_TIMEOUT_S,
                 keep_jobs: int = RENDER_KEEP_JOBS, keep_s: float = RENDER_KEEP_S,
                 context: ProcessContext | None = None,
                 video_source: VideoSource = render_video_file, root: Path | None = None):
        self.source = source
        self.video_source = video_source
        self.context = context
        self.workers = workers
        self.queue = queue
        self.timeout = timeout
        self.keep_jobs = keep_jobs
        self.keep_s = keep_s
        self.jobs: dict[str, Job] = {}
        self._root: Path | None = root
        self._supervisor: asyncio.Task[None] | None = None
        atexit.register(self.close)

    # ------------------------------------------------------------------ queries
    def _in_state(self, *states: str) -> list[Job]:
        return [j for j in self.jobs.values() if j.state in states]

    def get(self, job_id: str) -> Job:
        job = self.jobs.get(job_id)
        if job is None:
            raise ApiError(404, "render", f"no render job {job_id[:40]!r} (finished jobs are "
                           f"kept {self.keep_s:g} s)")
        return job

    def frame(self, job_id: str, index: int) -> bytes:
        """The PNG of a frame that is ready; 404 or 409 (not yet, or the job failed)."""
        job = self.get(job_id)
        if job.kind == "video":
            raise ApiError(404, "render", f"render job {job_id} is a video: fetch "
                           f"/api/render/{job_id}/video")
        if not 0 <= index < job.total:
            raise ApiError(404, "render", f"render job {job_id} has frames 0..{job.total - 1}, "
                           f"not {index}")
        path = job.folder / frame_name(index)
        if job.state in ("queued", "running") and not path.is_file():
            raise ApiError(409, "render", f"frame {index} of render job {job_id} is not "
                           f"ready yet ({job.ready()} of {job.total} done)")
        try:
            return path.read_bytes()
        except OSError:
            why = job.error["message"] if job.error else f"the job is {job.state}"
            raise ApiError(409, "render", f"frame {index} of render job {job_id} was not "
                           f"rendered: {why}") from None

    def video(self, job_id: str) -> Path:
        """The MP4 file of a finished video job; 404 for a key-frame job, 409 when it
        is not done (yet, or ever)."""
        job = self.get(job_id)
        if job.kind != "video":
            raise ApiError(404, "render", f"render job {job_id} is key frames, not a video")
        path = job.folder / VIDEO
        if job.state != "done" or not path.is_file():
            done, total = job.progress()
            why = (f"{done} of {total or '?'} frames drawn" if job.state in ("queued", "running")
                   else job.error["message"] if job.error else f"the job is {job.state}")
            raise ApiError(409, "render", f"the video of render job {job_id} is not ready: "
                           f"{why}")
        return path

    # ------------------------------------------------------------------ changes
    def submit(self, request: RenderRequest, lines: list[int], kind: str = "keyframes") -> Job:
        """Queue a job; 503 when the queue is full."""
        waiting = len(self._in_state("queued"))
        if len(self._in_state("running")) >= self.workers and waiting >= self.queue:
            raise busy(f"{self.workers} render job(s) running and {waiting} waiting",
                       retry_after=5)
        if self._root is None:
            self._root = Path(tempfile.mkdtemp(prefix="homesim-render-"))
        self._root.mkdir(parents=True, exist_ok=True)
        job_id = secrets.token_hex(8)
        job = Job(job_id, self._root / job_id, request, lines, kind)
        self.jobs[job_id] = job
        self._start_ready()
        loop = asyncio.get_running_loop()
        old = self._supervisor
        if old is not None and not old.done() and old.get_loop() is loop:
            old.cancel()  # it may be idling for minutes: watch closely from now on
        self._supervisor = loop.create_task(self._supervise())
        return job

    def cancel(self, job_id: str) -> Job:
        job = self.get(job_id)
        if job.state in ("queued", "running"):
            self._stop(job)
            job.state, job.finished = "cancelled", time.monotonic()
            self._start_ready()
        return job

    def close(self) -> None:
        """Stop every worker and delete every job's frames."""
        for job in self.jobs.values():
            self._stop(job)
        self.jobs.clear()
        if self._supervisor is not None:
            self._supervisor.cancel()
            self._supervisor = None
        if self._root is not None:
            shutil.rmtree(self._root, ignore_errors=True)
            self._root = None

    # ------------------------------------------------------------------ workers
    def _start_ready(self) -> None:
        free = self.workers - len(self._in_state("running"))
        for job in sorted(self._in_state("queued"), key=lambda j: j.created)[:max(free, 0)]:
            job.folder.mkdir(parents=True)
            target, source = ((run_video_job, self.video_source) if job.kind == "video"
                              else (run_job, self.source))
            job.process = (self.context or worker_context()).Process(
                target=target, args=(source, job.request, str(job.folder), self.timeout),
                name=f"homesim-render-{job.id}", daemon=True)
            job.process.start()
            job.state, job.started = "running", time.monotonic()

    def _stop(self, job: Job) -> None:
        if job.process is not None and job.process.is_alive():
            job.process.kill()
            job.process.join(timeout=5)

    def _finish(self, job: Job) -> None:
        """Read what a worker left: done, or its error."""
        job.finished = time.monotonic()
        error = job.folder / "error.json"
        if (job.folder / "done.json").is_file():
            job.state = "done"
        elif error.is_file():
            body = json.loads(error.read_text(encoding="utf-8"))
            job.state, job.error = "failed", {"status": body["status"], **body["error"]}
        else:
            job.state = "failed"
            job.error = {"status": 500, "kind": "internal", "message": "the render worker "
                         f"stopped without an answer (exit code {job.process.exitcode})"}
        job.process = None

    def _tick(self) -> None:
        now = time.monotonic()
        for job in self._in_state("running"):
            if job.process.exitcode is not None:
                job.process.join()
                self._finish(job)
            elif now - (job.started or now) > self.timeout:
                self._stop(job)
                job.state, job.finished, job.process = "failed", now, None
                job.error = {"status": 422, "kind": "render", "message": f"the render took "
                             f"longer than {self.timeout:g} s and was stopped; render fewer "
                             "steps or smaller frames"}
        self._start_ready()
        self._expire(now)

    def _expire(self, now: float) -> None:
        finished = sorted((j for j in self.jobs.values() if j.finished is not None),
                          key=lambda j: j.finished or 0.0, reverse=True)
        for rank, job in enumerate(finished):
            if rank >= self.keep_jobs or now - (job.finished or now) > self.keep_s:
                shutil.rmtree(job.folder, ignore_errors=True)
                del self.jobs[job.id]

    async def _supervise(self) -> None:
        """Watch workers while jobs are queued or running; expire old jobs."""
        while True:
            self._tick()
            if not self._in_state("queued", "running"):
                if not self.jobs:
                    return
                await asyncio.sleep(min(self.keep_s, 30.0))
                continue
            await asyncio.sleep(_POLL_S)


def _jobs(http: Request) -> RenderJobs:
    return http.app.state.renders


async def _queue(request: RenderRequest, http: Request, kind: str) -> Response:
    """Check a render request (501 without the render extra) and queue it; 202."""
    # In a thread: the first look imports mujoco (seconds), which must not stop the loop.
    await run_in_threadpool(programs.keyframe_renderer)  # 501 without the render extra
    if is_heavy(request):
        checked = await answer_or_gone(http.app.state.programs, render_plan, request,
                                       http.is_disconnected)
        if checked.status_code != 200:
            return checked
        plan = json.loads(bytes(checked.body))
    else:
        plan = await run_in_threadpool(render_plan, request)
    job = _jobs(http).submit(request, plan["lines"], kind)
    return SafeJSONResponse(job.to_json(), status_code=202)


@router.post("/render", status_code=202, response_class=SafeJSONResponse)
async def render(request: RenderRequest, http: Request) -> Response:
    """Queue a render of a program's key frames (one per step); 202 with the job's URL."""
    return await _queue(request, http, "keyframes")


@router.post("/render/video", status_code=202, response_class=SafeJSONResponse)
async def render_video(request: VideoRequest, http: Request) -> Response:
    """Queue a render of a program's whole video (MP4); 202 with the job's URL."""
    return await _queue(request, http, "video")


@router.get("/render/{job_id}", response_class=SafeJSONResponse)
async def render_status(job_id: str, http: Request) -> Response:
    """A render job's status and the frames ready so far."""
    jobs = _jobs(http)
    jobs._tick()  # the answer is current even between supervisor rounds
    return SafeJSONResponse(jobs.get(job_id).to_json())


@router.get("/render/{job_id}/frames/{index}", response_class=Response,
            responses={200: {"content": {"image/png": {}}}})
async def render_frame(job_id: str, index: int, http: Request) -> Response:
    """One key frame of a render job, as PNG."""
    png = _jobs(http).frame(job_id, index)
    return Response(png, media_type="image/png",
                    headers={"Cache-Control": "private, max-age=600"})


@router.get("/render/{job_id}/video", response_class=FileResponse,
            responses={200: {"content": {"video/mp4": {}}}})
async def render_video_file_route(job_id: str, http: Request) -> Response:
    """The video of a finished video job, as MP4 (H.264); range requests are answered."""
    jobs = _jobs(http)
    jobs._tick()
    return FileResponse(jobs.video(job_id), media_type="video/mp4",
                        headers={"Cache-Control": "private, max-age=600"})


@router.delete("/render/{job_id}", response_class=SafeJSONResponse)
async def cancel_render(job_id: str, http: Request) -> Response:
    """Cancel a queued or running render job (its frames so far stay available)."""
    return SafeJSONResponse(_jobs(http).cancel(job_id).to_json())
