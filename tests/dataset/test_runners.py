from homesim.dataset import generate_dataset
from tests.dataset.conftest import tiny_config, tree_hashes


def test_ray_tasks_make_the_same_bytes_as_the_serial_run(tiny_dataset, program_file, tmp_path):
    """Local Ray (started in this process, two workers): same shards, manifest, bytes."""
    out = tmp_path / "ray"
    summary = generate_dataset(tiny_config(program_file), out, workers=2)
    assert summary.ok == 3
    assert tree_hashes(out) == tree_hashes(tiny_dataset)
