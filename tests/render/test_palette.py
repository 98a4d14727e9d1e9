from homesim.render.palette import class_color


def test_colours_are_fixed_per_class_and_valid():
    assert class_color("wall") == class_color("wall")
    assert class_color("sofa") != class_color("tv")
    for name in ("wall", "coffeemaker", "toothbrush", "x"):
        rgba = class_color(name)
        assert len(rgba) == 4 and all(0.0 <= c <= 1.0 for c in rgba) and rgba[3] == 1.0
    assert class_color("coffeemaker") == class_color("coffeemaker")  # stable hash (CRC32)
