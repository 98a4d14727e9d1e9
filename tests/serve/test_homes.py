def test_homes_lists_builtin_homes_with_default(client):
    data = client.get("/api/homes").json()
    names = [h["name"] for h in data["homes"]]
    assert data["default"] == "scene1" and "scene1" in names and "scene5_trimmed" in names
    assert {h["name"]: h["geometry"] for h in data["homes"]}["scene1_trimmed"] is False
    assert "gen-0" in names


def test_generated_home_objects_and_no_files(client, tmp_path, monkeypatch):
    objects = client.get("/api/homes/gen-1/objects")
    assert objects.status_code == 200
    assert {r["class_name"] for r in objects.json()["rooms"]} >= {"kitchen", "bathroom"}
    from homesim.world import load_home

    load_home("scene1").save(tmp_path / "h.json")  # a valid home file ...
    monkeypatch.chdir(tmp_path)
    assert client.get("/api/homes/h.json/objects").status_code == 404  # ... is not served


def test_actions_are_grouped_in_the_nine_categories(client):
    data = client.get("/api/actions").json()
    assert [c["id"] for c in data["categories"]] == [
        "movement", "attention", "hands", "placing", "open_close", "devices", "body",
        "cleaning", "eating"]
    flat = {a["name"]: a for c in data["categories"] for a in c["actions"]}
    assert len(flat) == data["count"] == 42
    assert flat["PutBack"]["arity"] == 2 and flat["StandUp"]["arity"] == 0
    assert flat["SwitchOn"]["key"] == "SWITCHON" and flat["Walk"]["animated"] is True


def test_actions_serve_the_catalog_rows(client):
    from homesim.program import ACTIONS

    data = client.get("/api/actions").json()
    assert data["actions"] == [a.to_dict() for a in ACTIONS.values()]
    rows = {a["key"]: a for a in data["actions"]}
    assert rows["PUTBACK"]["connector"] == "on" and rows["PUTIN"]["connector"] == "into"
    assert rows["POUR"]["connector"] == "into" and rows["WALK"]["connector"] is None
    assert rows["PUTBACK"]["aliases"] == ["PUT"] and "LOOKAT_SHORT" in rows["LOOKAT"]["aliases"]


def test_action_rows_carry_what_the_editor_draws_and_reads(client):
    flat = {a["key"]: a for c in client.get("/api/actions").json()["categories"]
            for a in c["actions"]}
    assert flat["PUTIN"]["connector"] == "into" and flat["WALK"]["connector"] is None
    assert flat["PUTBACK"]["aliases"] == ["PUT"] and flat["PUTBACK"]["category"] == "placing"
    assert flat["POUR"]["needs"] == [[["DRINKABLE", "POURABLE"]], [["RECIPIENT"]]]


def test_objects_of_a_home_come_with_their_rooms(client):
    data = client.get("/api/homes/scene1/objects").json()
    by_id = {o["id"]: o for o in data["objects"]}
    assert by_id[410]["class_name"] == "tv" and by_id[410]["room"] == "livingroom"
    assert by_id[352]["class_name"] == "sofa" and by_id[352]["room_id"] == 319
    assert data["character"] not in by_id
    assert {r["class_name"] for r in data["rooms"]} == {
        "bathroom", "bedroom", "kitchen", "livingroom"}
    # Rooms are objects too ([Walk] <kitchen>), in their own room.
    assert by_id[319]["room"] == "livingroom"


def test_unknown_home_is_404_with_suggestion(client):
    r = client.get("/api/homes/scene9/objects")
    assert r.status_code == 404
    error = r.json()["error"]
    assert error["kind"] == "home"
    assert "unknown home 'scene9'" in error["message"] and "scene1" in error["message"]
