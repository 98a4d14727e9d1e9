import numpy as np
import pytest

from homesim.dataset import encode


def test_depth_round_trips_to_the_millimetre():
    depth = np.array([[0.0, 1.2344, 3.0], [29.9996, 0.0004, 70.0]], np.float32)
    back = encode.decode_depth(encode.encode_depth(depth))
    assert back.dtype == np.float32
    np.testing.assert_allclose(back, [[0.0, 1.234, 3.0], [30.0, 0.0, 65.535]], atol=1e-6)


def test_flow_round_trips_in_64ths_with_its_mask():
    flow = np.zeros((2, 3, 2), np.float32)
    flow[0, 0] = (1.5, -2.25)
    flow[0, 1] = (600.0, 0.0)  # out of range: marked invalid, not clipped
    flow[1, 2] = (0.01, 0.0)
    valid = np.ones((2, 3), bool)
    valid[1, 0] = False
    back, ok = encode.decode_flow(encode.encode_flow(flow, valid))
    assert back.shape == (2, 3, 2) and ok.shape == (2, 3)
    assert ok.tolist() == [[True, False, True], [False, True, True]]
    np.testing.assert_array_equal(back[0, 0], [1.5, -2.25])
    np.testing.assert_array_equal(back[0, 1], [0.0, 0.0])
    assert back[1, 2, 0] == pytest.approx(1 / 64)


def test_instances_become_legend_indices():
    order, index = encode.instance_lut([410, 12, 410])
    assert order.tolist() == [0, 410, 12] and index == {0: 0, 410: 1, 12: 2}
    seg = np.array([[0, 410], [12, 99999]], np.int32)
    codes = encode.InstanceCodes(index)
    assert encode.read_png16(encode.encode_instances(seg, codes)).tolist() == [[0, 1], [2, 0]]
    assert codes(np.array([-1, 5, 2**31 - 1])).tolist() == [0, 0, 0]
    assert encode.InstanceCodes({})(seg).tolist() == [[0, 0], [0, 0]]


def test_encoding_is_deterministic():
    rng = np.random.default_rng(0)
    depth = rng.uniform(0, 10, (24, 32)).astype(np.float32)
    assert encode.encode_depth(depth) == encode.encode_depth(depth.copy())
