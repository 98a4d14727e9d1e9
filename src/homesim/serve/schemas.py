"""Request bodies of the API (responses are plain JSON dicts built in `results`)."""

from __future__ import annotations

from pydantic import BaseModel, Field

from homesim.limits import (
    MAX_RENDER_HEIGHT,
    MAX_RENDER_VIDEO_FPS,
    MAX_RENDER_WIDTH,
    MAX_STEPS,
    MIN_RENDER_SIDE,
)

__all__ = ["MAX_STEPS", "ExecuteRequest", "ProgramRequest", "RenderRequest", "VideoRequest",
           "WriteRequest"]


class ProgramRequest(BaseModel):
    """A program text (ActivityPrograms format or steps only), optionally for a home."""

    program: str = Field(description="program text: title, description, blank line, steps")
    home: str | None = Field(default=None, description="built-in home to check node ids in")


class ExecuteRequest(BaseModel):
    """A program to run on a home.

    Run by `homesim.run_program`, as ``homesim run`` does. ``ground``: None (default)
    prepares and grounds a program when some object ref lacks a node id, and checks and
    runs a grounded one as it is; True grounds it anew even when it carries node ids;
    False reads ``(N)`` as node N, as the reference simulator does. ``repair``: insert
    the steps a program misses when it cannot run as written (default; the answer's
    ``repair`` lists them), or False for the strict answer.
    """

    program: str
    home: str
    ground: bool | None = None
    seed: int = Field(default=0, description="seed of preparation and grounding")
    repair: bool = Field(default=True, description="insert the steps a program misses")


class RenderRequest(BaseModel):
    """A program to render as key frames (one per step that runs: with ``repair``, the
    inserted steps too)."""

    program: str
    home: str
    width: int = Field(default=320, ge=MIN_RENDER_SIDE, le=MAX_RENDER_WIDTH)
    height: int = Field(default=240, ge=MIN_RENDER_SIDE, le=MAX_RENDER_HEIGHT)
    seed: int = 0
    repair: bool = Field(default=True, description="insert the steps a program misses")


class VideoRequest(RenderRequest):
    """A program to render as one video of the whole program (MP4, H.264)."""

    fps: int = Field(default=12, ge=1, le=MAX_RENDER_VIDEO_FPS)


class WriteRequest(BaseModel):
    """A description to write a program for (``homesim learn write``), in a built-in home.

    Title and description are checked against `homesim.limits.MAX_DESCRIPTION_CHARS`.
    Without a title, the writer guesses the activity from the description."""

    description: str
    title: str | None = None
    home: str = Field(default="scene1", description="built-in home to run the program in")
    seed: int = Field(default=0, description="seed of preparation and grounding")
