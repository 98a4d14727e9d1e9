import json

import numpy as np
import pytest

import homesim
from homesim.errors import DataError
from homesim.render import load_recording, render_program

pytestmark = pytest.mark.render

PROGRAM = "[Walk] <cup> (21)\n[Grab] <cup> (21)\n[Walk] <tv> (22)\n[SwitchOn] <tv> (22)\n"


@pytest.fixture(scope="module")
def recording(tmp_path_factory, gl):
    from homesim.world.graph import EnvironmentGraph

    from .conftest import box_home_dict, ran

    out = tmp_path_factory.mktemp("rec") / "r"
    g = EnvironmentGraph.from_dict(box_home_dict(), source="box home")
    calls = []
    result = render_program(ran(PROGRAM, g), out, width=64, height=48, fps=6, seed=3,
                            progress=lambda d, t: calls.append((d, t)))
    return result, load_recording(out), g, calls


def test_result_and_progress(recording):
    result, rec, _, calls = recording
    assert result.num_frames == rec.num_frames > 10
    assert calls[-1] == (result.num_frames, result.num_frames)
    assert result.agent == "female2"  # seed 3 picks the fourth agent
    assert [s.step for s in result.steps] == [str(s) for s in
                                              homesim.parse_program(PROGRAM).steps]


def test_loaded_frames_have_every_channel(recording):
    _, rec, g, _ = recording
    f = rec.frame(rec.num_frames // 2)
    assert f["depth"].shape == (48, 64) and f["depth"].dtype == np.float32
    assert f["class"].dtype == np.uint16 and f["instance"].dtype == np.int32
    assert f["flow"].shape == (48, 64, 2) and f["flow"].dtype == np.float32
    assert f["flow_valid"].shape == (48, 64) and f["flow_valid"].dtype == bool
    assert set(np.unique(f["instance"]).tolist()) <= set(g.nodes) | {0}
    rgb = rec.rgb()
    assert rgb.shape == (rec.num_frames, 48, 64, 3)
    pf = rec.per_frame
    t = rec.num_frames
    assert pf["camera"].shape == (t,) and pf["world_to_cam"].shape == (t, 4, 4)
    assert pf["intrinsics"].shape == (t, 3, 3) and pf["joints3d"].shape == (t, 16, 3)
    assert pf["joints2d"].shape == (t, 16, 2) and pf["joints_visible"].shape == (t, 16)


def test_legends_match_the_graph(recording):
    _, rec, g, _ = recording
    assert rec.classes[0] == "background"
    for nid, cls in rec.instances.items():
        assert g.node(nid).class_name == cls
    f = rec.frame(0)
    inst = rec.meta["instances"]
    for nid in np.unique(f["instance"]):
        if nid:
            assert np.all(f["class"][f["instance"] == nid] == inst[str(nid)]["class_id"])


def test_steps_have_start_and_end_frames(recording):
    _, rec, _, _ = recording
    steps = rec.steps
    assert [s.index for s in steps] == [0, 1, 2, 3]
    assert steps[0].start_frame >= 0 and steps[-1].end_frame == rec.num_frames - 1
    assert all(steps[i].end_frame + 1 == steps[i + 1].start_frame for i in range(3))


def test_loader_errors_name_the_folder(tmp_path, recording):
    with pytest.raises(DataError, match="not a recording"):
        load_recording(tmp_path)
    (tmp_path / "meta.json").write_text(json.dumps({"format": 99}))
    with pytest.raises(DataError, match="format 99"):
        load_recording(tmp_path)
    _, rec, _, _ = recording
    with pytest.raises(DataError, match="out of range"):
        rec.frame(rec.num_frames)


def test_same_seed_gives_the_same_recording(tmp_path, box_home, gl):
    from .conftest import ran

    for name in ("a", "b"):
        render_program(ran("[Walk] <tv> (22)\n", box_home), tmp_path / name, width=32,
                       height=24, fps=4, seed=5)
    a, b = load_recording(tmp_path / "a"), load_recording(tmp_path / "b")
    assert a.num_frames == b.num_frames
    for i in (0, a.num_frames - 1):
        for key, arr in a.frame(i).items():
            np.testing.assert_array_equal(arr, b.frame(i)[key], err_msg=key)
    np.testing.assert_array_equal(a.per_frame["joints2d"], b.per_frame["joints2d"])



def test_flow_is_invalid_across_cuts_and_after_the_last_frame(recording):
    _, rec, _, _ = recording
    cut = rec.per_frame["cut"]
    assert cut.any()  # the test can fail: the camera changes at least once
    for i in np.flatnonzero(cut):
        assert not rec.frame(int(i))["flow_valid"].any()
    assert not rec.frame(rec.num_frames - 1)["flow_valid"].any()
    kept = next(i for i in range(rec.num_frames - 1) if not cut[i])
    f = rec.frame(kept)
    assert f["flow_valid"].any() and not f["flow_valid"][f["depth"] == 0].any()


def test_a_few_frames_are_read_without_decoding_the_whole_video(box_home, tmp_path, gl,
                                                                 monkeypatch):
    from homesim.render import groundtruth, load_recording, render_program

    from .conftest import ran

    rec = render_program(ran("[Walk] <tv> (22)\n[SwitchOn] <tv> (22)\n", box_home),
                         tmp_path / "rec", width=32, height=24, fps=5, seed=2)
    loaded = load_recording(rec.out_dir)
    every = loaded.rgb()
    decoded = []
    original = groundtruth.iter_video

    def counting(*args, **kwargs):
        for frame in original(*args, **kwargs):
            decoded.append(1)
            yield frame

    monkeypatch.setattr(groundtruth, "iter_video", counting)
    some = loaded.rgb_frames([1, 3])
    assert sorted(some) == [1, 3] and len(decoded) == 4  # stopped after the last asked for
    np.testing.assert_array_equal(some[3], every[3])
