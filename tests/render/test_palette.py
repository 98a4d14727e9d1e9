from homesim.render.palette import class_color


def test_colours_are_fixed_per_class_and_valid():
    assert class_color("wall") == class_color("wall")
    assert class_color("sofa") != class_color("tv")
    for name in ("wall", "coffeemaker", "toothbrush", "x"):
        rgba = class_color(name)
        assert len(rgba) == 4 and all(0.0 <= c <= 1.0 for c in rgba) and rgba[3] == 1.0
    assert class_color("coffeemaker") == class_color("coffeemaker")  # stable hash (CRC32)


def test_a_theme_varies_with_the_seed_and_keeps_electronics_dark():
    from homesim.render.palette import Theme, themed_color

    grey = (0.5, 0.5, 0.5, 1.0)
    sofas = {themed_color(Theme.of(seed), "sofa", grey) for seed in range(6)}
    assert len(sofas) >= 3  # not the same sofa in every home
    for seed in range(6):
        theme = Theme.of(seed)
        tv = themed_color(theme, "tv", grey)
        assert max(tv[:3]) < 0.15  # electronics dark
        assert themed_color(theme, "pillow", grey)[:3] != themed_color(theme, "sofa", grey)[:3]
        assert themed_color(theme, "apple", (0.75, 0.12, 0.1, 1.0)) == (0.75, 0.12, 0.1, 1.0)


def test_one_accent_runs_through_a_home():
    import colorsys

    from homesim.render.palette import Theme, themed_color

    theme = Theme.of(4)
    hues = [colorsys.rgb_to_hsv(*themed_color(theme, c, (0, 0, 0, 1))[:3])[0]
            for c in ("pillow", "rug", "curtains", "towel")]
    assert max(hues) - min(hues) < 0.06
