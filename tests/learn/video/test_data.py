"""Episodes of a data set folder held small for learning."""

import pytest


def test_a_folder_that_is_not_a_data_set_is_refused(tmp_path):
    from homesim.errors import HomesimError
    from homesim.learn.video.data import load_episodes

    with pytest.raises(HomesimError, match="not a data set folder"):
        load_episodes(tmp_path)
