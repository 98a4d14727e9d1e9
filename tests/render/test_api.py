import numpy as np
import pytest

import homesim
from homesim.errors import ExecutionError, HomesimError
from homesim.render import render_keyframes, render_program

from .conftest import ran

pytestmark = pytest.mark.render


def test_keyframes_one_per_step(box_home, gl):
    frames = render_keyframes(ran("[Walk] <tv> (22)\n[SwitchOn] <tv> (22)\n", box_home),
                              width=64, height=48, seed=1)
    assert [i for i, _ in frames] == [0, 1]
    assert all(f.shape == (48, 64, 3) and f.dtype == np.uint8 for _, f in frames)
    # The TV's screen lights up after SwitchOn: the second frame is not the first.
    assert not np.array_equal(frames[0][1], frames[1][1])


def test_the_run_is_animated_as_it_was_grounded(box_home, gl):
    """Render takes the run's bindings and standing spots; it runs nothing again."""
    from homesim.render import animate

    run = ran("[Walk] <television> (1)\n[SwitchOn] <television> (1)\n", box_home,
              reference=False)
    assert run.bindings is not None and dict(run.bindings) == {("television", 1): 22}
    animation = animate(run, width=32, height=24, fps=4, seed=0)
    assert animation.program is run.result.program
    assert [s.step for s in animation.steps] == [str(s) for s in run.result.program.steps]
    assert animation.timeline.focus == [22, 22]  # the bound node, from the trace
    assert len(render_keyframes(run, width=32, height=24)) == 2


def test_a_run_that_cannot_be_rendered_is_refused_before_drawing(box_home, tmp_path):
    from homesim.render import animate

    no_trace = homesim.run_program(homesim.parse_program("[Walk] <tv> (22)"), box_home,
                                   reference=True)
    with pytest.raises(HomesimError, match=r"trace=True"):
        animate(no_trace, width=32, height=24, fps=4)
    ungrounded = ran("[Walk] <garage> (1)\n", box_home, reference=False)
    assert ungrounded.stage == "grounding"
    with pytest.raises(ExecutionError, match="cannot render a program that does not run: "
                                             "step 1 "):
        render_program(ungrounded, tmp_path / "x", width=32, height=24)
    assert not (tmp_path / "x").exists()


def test_program_that_does_not_execute_is_refused(box_home, tmp_path, gl):
    with pytest.raises(ExecutionError, match=r"step 1 \[Grab\] <tv> \(22\)"):
        render_program(ran("[Grab] <tv> (22)\n", box_home), tmp_path / "x", width=32,
                       height=24)
    assert not (tmp_path / "x").exists()


@pytest.mark.parametrize(("kwargs", "pattern"), [
    ({"width": 33}, "must be even"),
    ({"width": 2}, "out of range"),
    ({"fps": 0}, "fps 0 out of range"),
    ({"agent": "robot"}, "unknown agent 'robot'"),
])
def test_bad_arguments(box_home, tmp_path, kwargs, pattern, gl):
    args = {"width": 32, "height": 24, **kwargs}
    with pytest.raises(HomesimError, match=pattern):
        render_program(ran("[Walk] <tv> (22)\n", box_home), tmp_path / "x", **args)


def test_existing_recording_is_not_overwritten(box_home, tmp_path, gl):
    (tmp_path / "meta.json").write_text("{}")
    with pytest.raises(HomesimError, match="already holds a recording"):
        render_program(ran("[Walk] <tv> (22)\n", box_home), tmp_path, width=32, height=24)
    assert (tmp_path / "meta.json").read_text() == "{}"


def test_a_video_over_the_frames_x_pixels_limit_is_refused_before_drawing(
        box_home, tmp_path, gl, monkeypatch):
    from homesim.errors import LimitError
    from homesim.render import api

    monkeypatch.setattr(api, "MAX_VIDEO_PIXEL_FRAMES", 32 * 24 * 3)  # 3 frames
    with pytest.raises(LimitError, match="MAX_VIDEO_PIXEL_FRAMES") as e:
        render_program(ran("[Walk] <tv> (22)\n", box_home), tmp_path / "x", width=32,
                       height=24)
    assert e.value.limit == "MAX_VIDEO_PIXEL_FRAMES"
    assert not (tmp_path / "x").exists()


def test_render_video_writes_the_recordings_frames_as_mp4_only(box_home, tmp_path, gl):
    import av

    from homesim.render import load_recording, render_video

    run = ran("[Walk] <tv> (22)\n[SwitchOn] <tv> (22)\n", box_home)
    calls = []
    path = tmp_path / "v.mp4"
    n = render_video(run, path, width=64, height=48, fps=5, seed=2,
                     progress=lambda done, total: calls.append((done, total)))
    rec = render_program(run, tmp_path / "rec", width=64, height=48, fps=5, seed=2)
    assert n == rec.num_frames == load_recording(rec.out_dir).rgb().shape[0]
    assert calls[-1] == (n, n) and len(calls) == n
    with av.open(str(path)) as container:
        stream = container.streams.video[0]
        assert (stream.width, stream.height, stream.average_rate) == (64, 48, 5)
        assert stream.codec_context.name == "h264"
        assert sum(1 for _ in container.decode(stream)) == n
    assert {x.name for x in tmp_path.iterdir()} == {"v.mp4", "rec"}  # no ground truth
    # One encoder for both: the same frames give the same bytes, index first.
    data = path.read_bytes()
    assert data == (rec.out_dir / "video.mp4").read_bytes()
    assert data.index(b"moov") < data.index(b"mdat")


def test_a_hands_on_step_is_shown_at_its_effect(box_home):
    """Key frames: the hand on the object (what its close-up is aimed at), not the arm
    back at rest; other steps at their last frame."""
    from homesim.render.api import animate, key_frames

    tl = animate(ran("[Walk] <cup> (21)\n[Grab] <cup> (21)\n[Walk] <tv> (22)\n", box_home),
                 width=32, height=24, fps=10, seed=0, agent="male1").timeline
    (grab,) = tl.interactions
    assert key_frames(tl) == [tl.step_frames[0][1], grab.peak, tl.step_frames[2][1]]
    assert grab.peak < tl.step_frames[1][1]
