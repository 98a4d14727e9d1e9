import numpy as np

from homesim.render.flow import backproject, intrinsics, optical_flow, project, world_to_cam


def _camera_looking_along_x(pos):
    # MuJoCo camera axes as columns: x = image right (-y world), y = up (+z), z = back (-x)
    xmat = np.array([[0, 0, -1], [-1, 0, 0], [0, 1, 0]], float)
    return world_to_cam(np.asarray(pos, float), xmat.reshape(-1))


def test_project_and_backproject_are_inverse():
    k = intrinsics(64, 48, 60.0)
    w2c = _camera_looking_along_x([0, 0, 1])
    depth = np.full((48, 64), 3.0, np.float32)
    pts = backproject(depth, k, w2c)
    np.testing.assert_allclose(pts[..., 0], 3.0, atol=1e-9)  # all on the plane x = 3
    uv, z = project(pts.reshape(-1, 3), k, w2c)
    u, v = np.meshgrid(np.arange(64), np.arange(48))
    np.testing.assert_allclose(uv, np.stack([u, v], -1).reshape(-1, 2), atol=1e-9)
    np.testing.assert_allclose(z, 3.0)


def test_flow_of_a_geom_moving_sideways_and_of_a_moving_camera():
    w, h = 64, 48
    k = intrinsics(w, h, 60.0)
    w2c = _camera_looking_along_x([0, 0, 1])
    depth = np.full((h, w), 4.0, np.float32)
    ids = np.zeros((h, w), np.int32)  # every pixel on geom 0
    xpos0 = np.zeros((1, 3))
    xmat = np.eye(3).reshape(1, 9)
    # The geom moves 0.2 m to world -y = image right: flow u = f * 0.2 / 4.
    xpos1 = np.array([[0.0, -0.2, 0.0]])
    flow, valid = optical_flow(depth, ids, k, w2c, k, w2c, xpos0, xmat, xpos1, xmat)
    u = np.arange(w) + flow[0, :, 0]
    np.testing.assert_array_equal(valid, np.broadcast_to(u < w - 0.5, (h, w)))  # off the right
    np.testing.assert_allclose(flow[..., 0], k[0, 0] * 0.2 / 4.0, rtol=1e-5)
    np.testing.assert_allclose(flow[..., 1], 0.0, atol=1e-5)
    # Static geom, camera rises 0.1 m: the scene moves down the image by f * 0.1 / 4.
    w2c_up = _camera_looking_along_x([0, 0, 1.1])
    flow, _ = optical_flow(depth, ids, k, w2c, k, w2c_up, xpos0, xmat, xpos0, xmat)
    np.testing.assert_allclose(flow[..., 1], k[1, 1] * 0.1 / 4.0, rtol=1e-5)
    np.testing.assert_allclose(flow[..., 0], 0.0, atol=1e-5)


def test_flow_is_zero_off_geometry_and_for_still_things():
    k = intrinsics(32, 24, 60.0)
    w2c = _camera_looking_along_x([0, 0, 1])
    depth = np.full((24, 32), 2.0, np.float32)
    ids = np.full((24, 32), -1, np.int32)
    ids[:, :16] = 0
    x = np.zeros((1, 3))
    m = np.eye(3).reshape(1, 9)
    flow, valid = optical_flow(depth, ids, k, w2c, k, w2c, x, m, x, m)
    assert flow.shape == (24, 32, 2) and flow.dtype == np.float32
    assert not flow.any()
    assert valid.dtype == bool
    np.testing.assert_array_equal(valid, ids >= 0)  # no point off geometry


def test_rotating_geom_flow_matches_projection():
    k = intrinsics(40, 30, 50.0)
    w2c = _camera_looking_along_x([0, 0, 1])
    depth = np.full((30, 40), 3.0, np.float32)
    ids = np.zeros((30, 40), np.int32)
    c, s = np.cos(0.1), np.sin(0.1)
    rot = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])  # yaw 0.1 rad about the geom origin
    x0 = np.array([[3.0, 0.0, 1.0]])
    flow, _ = optical_flow(depth, ids, k, w2c, k, w2c, x0, np.eye(3).reshape(1, 9), x0,
                           rot.reshape(1, 9))
    pts = backproject(depth, k, w2c).reshape(-1, 3)
    moved = (pts - x0) @ rot.T + x0
    uv, _ = project(moved, k, w2c)
    u, v = np.meshgrid(np.arange(40), np.arange(30))
    expect = uv - np.stack([u, v], -1).reshape(-1, 2)
    np.testing.assert_allclose(flow.reshape(-1, 2), expect, atol=1e-4)


def test_points_behind_or_beside_the_next_camera_have_no_valid_flow():
    """The next camera stands 2 m ahead, inside the plane of points, looking the same way:
    every point is behind it; a camera turned a little sees only part of them."""
    w, h = 32, 24
    k = intrinsics(w, h, 60.0)
    w2c = _camera_looking_along_x([0, 0, 1])
    depth = np.full((h, w), 1.0, np.float32)
    ids = np.zeros((h, w), np.int32)
    x, m = np.zeros((1, 3)), np.eye(3).reshape(1, 9)
    ahead = _camera_looking_along_x([2.0, 0, 1])
    flow, valid = optical_flow(depth, ids, k, w2c, k, ahead, x, m, x, m)
    assert not valid.any()
    assert np.abs(flow).max() > 0  # the flow is there, but not to be used
    shifted = _camera_looking_along_x([0, 0.3, 1])  # 0.3 m to the left: the right side leaves
    flow, valid = optical_flow(depth, ids, k, w2c, k, shifted, x, m, x, m)
    uv = np.stack(np.meshgrid(np.arange(w), np.arange(h)), -1) + flow
    inside = (uv[..., 0] >= -0.5) & (uv[..., 0] < w - 0.5)
    assert 0 < valid.sum() < valid.size
    np.testing.assert_array_equal(valid, inside)
