import json

import pytest

from homesim.dataset import DatasetConfig, generate_dataset
from homesim.dataset.generate import generate_plan
from homesim.dataset.layout import Layout
from homesim.dataset.manifest import read_manifest
from homesim.dataset.plan import PAPER, Plan, load_plan, part_configs, read_plan
from homesim.errors import GraphError, HomesimError
from homesim.world.homes import load_home
from tests.dataset.conftest import tiny_config

TINY = Plan.from_dict({
    "name": "tiny",
    "parts": [{"name": "train", "role": "train", "homes": ["scene1"], "agents": ["male1"],
               "share": 0.5},
              {"name": "val", "role": "val", "homes": ["scene2"], "agents": ["female1"],
               "share": 0.25},
              {"name": "test", "role": "test", "homes": ["scene1"], "agents": ["male2"],
               "share": 0.25}],
    "rows": [{"row": "all", "label": "all test episodes", "parts": ["test"]}]})


def test_the_paper_plan_trains_on_most_and_never_tests_validation():
    counts = PAPER.counts(5200)
    assert sum(counts.values()) == 5200 and counts["train"] / 5200 >= 0.70
    roles = {p.name: p.role for p in PAPER.parts}
    tested = {q for _, _, parts in PAPER.rows for q in parts}
    assert all(roles[q] == "test" for q in tested) and "val" not in tested
    homes = {p.name: set(p.homes) for p in PAPER.parts}
    unseen = homes["test-unseen-homes"]
    assert all(not unseen & h for name, h in homes.items() if name != "test-unseen-homes")
    assert not homes["val"] & (homes["train"] | unseen)
    assert homes["test-seen"] == homes["test-unseen-agents"] == homes["train"]
    train_agents = set(PAPER.part("train").agents)
    assert set(PAPER.part("test-seen").agents) == train_agents
    assert not set(PAPER.part("test-unseen-agents").agents) & train_agents


def test_parts_draw_their_own_streams():
    configs = part_configs(PAPER, 5200, 0, DatasetConfig(width=64, height=48, fps=4))
    assert len({c.seed for c in configs.values()}) == len(configs)
    assert configs["train"].width == 64 and configs["train"].agents == ("male1", "female1")
    assert part_configs(PAPER, 5200, 1, DatasetConfig())["train"].seed != configs["train"].seed


def test_a_plan_that_tests_validation_is_refused(tmp_path):
    bad = PAPER.to_dict()
    bad["rows"].append({"row": "leak", "parts": ["val"]})
    with pytest.raises(HomesimError, match="row leak: pools 'val', not a test part"):
        Plan.from_dict(bad)
    bad = PAPER.to_dict()
    bad["parts"][0]["share"] = 0.5
    with pytest.raises(HomesimError, match=r"shares add up to 0\.780, not 1"):
        Plan.from_dict(bad)
    bad = PAPER.to_dict()
    bad["parts"][1]["agents"] = ["robot"]
    with pytest.raises(HomesimError, match="agent 'robot': choose from"):
        Plan.from_dict(bad)
    path = tmp_path / "plan.json"
    path.write_text(json.dumps(PAPER.to_dict()))
    assert load_plan(str(path)) == PAPER
    with pytest.raises(HomesimError, match="--plan nope: no such plan file; built-in"):
        load_plan("nope")
    path.write_text("{")
    with pytest.raises(HomesimError, match="cannot read"):
        load_plan(str(path))


def test_agents_are_drawn_from_the_option():
    with pytest.raises(HomesimError, match="agent 'robot': choose from male1"):
        DatasetConfig(agents=("robot",))
    config = DatasetConfig(agents=("female2",))
    assert DatasetConfig.from_dict(config.to_dict()) == config
    old = config.to_dict()
    del old["agents"]  # a folder begun before --agents: all four
    assert DatasetConfig.from_dict(old).agents == DatasetConfig().agents


@pytest.fixture(scope="module")
def tiny_plan(gl, program_file, tmp_path_factory):
    out = tmp_path_factory.mktemp("plan") / "plan"
    summaries = generate_plan(TINY, 4, out, tiny_config(program_file), workers=0)
    return out, summaries


def test_a_plan_is_made_in_its_parts_and_resumes(tiny_plan, program_file):
    out, summaries = tiny_plan
    assert {k: s.ok for k, s in summaries.items()} == {"train": 2, "val": 1, "test": 1}
    for part in TINY.parts:
        rows = read_manifest(out / part.name / "episodes.parquet")
        assert {r["agent"] for r in rows} <= set(part.agents)
        assert {r["home"] for r in rows} <= set(part.homes)
    folder = read_plan(out)
    assert folder is not None and folder.plan == TINY and folder.role("val") == "val"
    assert read_plan(out / "train") is None
    before = (out / "plan.json").read_bytes()
    base = tiny_config(program_file)
    generate_plan(TINY, 4, out, base, workers=0)  # all done: nothing made again
    assert (out / "plan.json").read_bytes() == before
    with pytest.raises(HomesimError, match="holds a plan made with other options"):
        generate_plan(TINY, 5, out, base, workers=0)


def test_the_card_of_a_plan_counts_parts_and_coverage(tiny_plan, tmp_path):
    from homesim.dataset.card import write_plan_card

    out, _ = tiny_plan
    paths = write_plan_card(out, tmp_path / "card")
    assert sorted(p.name for p in paths) == ["actions.png", "contact_sheet.png",
                                             "objects.png", "stats.json"]
    stats = json.loads((tmp_path / "card" / "stats.json").read_text())
    assert {k: v["made"] for k, v in stats["parts"].items()} == {"train": 2, "val": 1,
                                                                "test": 1}
    assert stats["train_share"] == 0.5 and stats["parts"]["val"]["role"] == "val"
    # One program file of two steps: every test step class is a training one.
    row = stats["coverage"]["all"]
    assert (row["classes_seen"], row["steps_seen"], row["test_classes"]) == (1.0, 1.0, 2)


def test_coverage_counts_classes_and_steps():
    from homesim.dataset.card import coverage
    from homesim.knowledge.datasets import ActivityDataset, ActivityProgram
    from homesim.program.parse import parse_program

    def ds(*texts: str) -> ActivityDataset:
        return ActivityDataset([ActivityProgram(str(i), parse_program(t), "x")
                                for i, t in enumerate(texts)], "x")

    train = ds("[Walk] <tv> (1)\n[SwitchOn] <tv> (1)", "[Walk] <tv> (2)")
    test = ds("[Walk] <tv> (1)\n[Grab] <cup> (1)\n[Walk] <tv> (1)")
    c = coverage(train, test)
    assert c["classes_seen"] == 0.5 and c["steps_seen"] == pytest.approx(2 / 3)
    assert c["classes_seen_5"] == 0 and c["train_classes"] == 2


def test_a_home_file_works_where_a_name_does(gl, program_file, tmp_path):
    path = tmp_path / "my_home.json"
    load_home("scene1").save(path)
    config = DatasetConfig(**{**tiny_config(program_file, n=1).__dict__,
                              "homes": (str(path),)})
    summary = generate_dataset(config, tmp_path / "data", workers=0)
    assert summary.ok == 1
    assert read_manifest(tmp_path / "data" / "episodes.parquet")[0]["home"] == str(path)
    missing = DatasetConfig(**{**config.__dict__, "homes": (str(tmp_path / "none.json"),)})
    with pytest.raises(GraphError, match=r"none.json: cannot read graph file \(No such"):
        generate_dataset(missing, tmp_path / "other", workers=0)
    assert not (tmp_path / "other").exists()
    assert Layout(tmp_path / "data").finished_rows()
