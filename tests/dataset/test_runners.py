from homesim.dataset import generate_dataset
from tests.dataset.conftest import tiny_config, tree_hashes


def test_ray_tasks_make_the_same_bytes_as_the_serial_run(tiny_dataset, program_file, tmp_path):
    """Local Ray (started in this process, two workers): same shards, manifest, bytes."""
    out = tmp_path / "ray"
    summary = generate_dataset(tiny_config(program_file), out, workers=2)
    assert summary.ok == 3
    assert tree_hashes(out) == tree_hashes(tiny_dataset)


def test_episodes_go_in_order_then_the_last_ones_longest_first():
    from homesim.dataset.runners import submission_stack
    from homesim.dataset.spec import EpisodeSpec

    def spec(index: int, steps: int) -> EpisodeSpec:
        program = "Title\nDescription\n\n" + "\n".join(["[Walk] <sofa> (1)"] * steps)
        return EpisodeSpec(index, f"p{index}", program, "scene1", "male1", 0, 0, 0, 0, 1.0)

    specs = [spec(0, 1), spec(1, 2), spec(2, 5), spec(3, 1), spec(4, 5)]
    stack = submission_stack(specs, tail=3)
    assert [stack.pop().index for _ in range(5)] == [0, 1, 2, 4, 3]
    stack = submission_stack(specs, tail=10)
    assert [stack.pop().index for _ in range(5)] == [2, 4, 1, 0, 3]


def test_cpu_tasks_rasterize_in_their_own_thread():
    from homesim.dataset.runners import task_environment

    assert task_environment(False)["LP_NUM_THREADS"] == "0"
    assert task_environment(True) == {"MUJOCO_GL": "egl"}
