import numpy as np
from PIL import Image

from homesim.render.sheet import contact_sheet


def test_sheet_lays_out_labelled_frames(tmp_path):
    frames = [(f"{i}. [Walk] <tv> (1)", np.full((24, 32, 3), 40 * i, np.uint8)) for i in range(5)]
    path = contact_sheet(frames, tmp_path / "s.png", columns=3, title="t")
    img = Image.open(path)
    assert img.size == (3 * 32, 22 + 2 * (24 + 18))
    assert np.asarray(img)[22 + 18 + 12, 32 + 16].tolist() == [40, 40, 40]  # frame 1
