"""Tests of the Python package: the same floor plan as the command line, from any input form,
and bad input refused with a message.

``make test-python`` runs them after ``pip install ./python`` in a fresh virtual environment,
with ``KSMCMC_BIN`` the command-line tool built from the same tree.
"""

import json
import math
import os
import subprocess
import tempfile
import threading

import numpy as np
import pytest

import ksmcmc
from ksmcmc import mln

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SAMPLE = os.path.join(REPO, "samples", "office-small", "map.yaml")
# Short chains keep the tests quick; the same count goes to the command line.
ITERATIONS = 3000


def read_pgm16(path):
    """A binary 16-bit PGM (labels.pgm) as a uint16 array."""
    with open(path, "rb") as f:
        data = f.read()
    fields, pos = [], 0
    while len(fields) < 4:
        while data[pos : pos + 1].isspace():
            pos += 1
        start = pos
        while not data[pos : pos + 1].isspace():
            pos += 1
        fields.append(data[start:pos])
    assert fields[0] == b"P5" and fields[3] == b"65535", fields
    width, height = int(fields[1]), int(fields[2])
    return np.frombuffer(data[pos + 1 :], dtype=">u2").reshape(height, width).astype(np.uint16)


def cli(*args):
    """Runs the command-line tool of the same tree."""
    binary = os.environ.get("KSMCMC_BIN") or os.path.join(REPO, "target", "debug", "ksmcmc")
    if not os.path.exists(binary):
        pytest.skip(f"no ksmcmc binary at {binary} (set KSMCMC_BIN)")
    return subprocess.run([binary, *args], check=True, capture_output=True, text=True)


def drawn_office():
    """A small office drawn as map_saver's pixels (0 wall, 254 free, 205 unknown): a corridor
    along the top and three rooms below it, each with a 1 m door, at 5 cm cells."""
    pixels = np.full((150, 240), 205, dtype=np.uint8)
    pixels[10:140, 10:230] = 0
    pixels[12:48, 12:228] = 254  # the corridor, 1.8 m wide
    for x0 in (12, 85, 158):
        pixels[50:138, x0 : x0 + 70] = 254  # a room of 3.5 x 4.4 m
        pixels[48:50, x0 + 25 : x0 + 45] = 254  # its door into the corridor
    return pixels


def as_occupancy(pixels):
    """The same cells as nav_msgs/OccupancyGrid values: 100 occupied, 0 free, -1 unknown."""
    grid = np.full(pixels.shape, -1, dtype=np.int8)
    grid[pixels == 0] = 100
    grid[pixels == 254] = 0
    return grid


def test_a_path_gives_the_command_lines_labels_and_world():
    plan = ksmcmc.floorplan(SAMPLE, seed=1, iterations=ITERATIONS)
    with tempfile.TemporaryDirectory() as out:
        cli("floorplan", SAMPLE, "--seed", "1", "--iterations", str(ITERATIONS), "--out", out)
        expected = read_pgm16(os.path.join(out, "labels.pgm"))
        with open(os.path.join(out, "world.json")) as f:
            world = json.load(f)
    assert plan.labels.dtype == np.uint16
    assert plan.labels.shape == expected.shape
    assert np.array_equal(plan.labels, expected)
    assert plan.world == world
    assert len(plan.rooms) >= 3
    assert {r["id"] for r in plan.rooms} == set(np.unique(plan.labels)) - {0}


def test_save_writes_the_command_lines_files_byte_for_byte():
    plan = ksmcmc.floorplan(SAMPLE, seed=1, iterations=ITERATIONS)
    with tempfile.TemporaryDirectory() as out, tempfile.TemporaryDirectory() as mine:
        cli("floorplan", SAMPLE, "--seed", "1", "--iterations", str(ITERATIONS), "--out", out)
        names = sorted(os.path.basename(p) for p in plan.save(mine))
        assert names == sorted(os.listdir(out))
        for name in names:
            with open(os.path.join(out, name), "rb") as a, open(os.path.join(mine, name), "rb") as b:
                theirs, ours = a.read(), b.read()
            if name == "report.json":
                # The same report but for the clock: seconds and rates differ run to run.
                timed = ("seconds", "iterations_per_second")
                t, o = json.loads(theirs), json.loads(ours)
                for k in timed:
                    t.pop(k, None)
                    o.pop(k, None)
                assert t == o
            else:
                assert theirs == ours, name


def test_the_same_seed_gives_the_same_plan():
    a = ksmcmc.floorplan(SAMPLE, seed=5, iterations=ITERATIONS)
    b = ksmcmc.floorplan(SAMPLE, seed=5, iterations=ITERATIONS)
    assert np.array_equal(a.labels, b.labels) and a.world == b.world


def test_pixels_and_an_occupancy_grid_of_the_same_cells_give_the_same_labels():
    pixels = drawn_office()
    a = ksmcmc.floorplan(pixels, resolution=0.05, iterations=ITERATIONS)
    b = ksmcmc.floorplan(as_occupancy(pixels), resolution=0.05, iterations=ITERATIONS)
    assert np.array_equal(a.labels, b.labels)
    assert a.world == b.world
    # The drawn office is explained: its corridor and rooms are rooms of the plan.
    assert len(a.rooms) >= 3, a.rooms
    assert a.labels[30, 120] != 0 and a.labels[100, 47] != 0
    assert a.labels[30, 120] != a.labels[100, 47]


def test_a_room_nobody_entered_leaves_placeholders_on_free_cells():
    pixels = drawn_office()
    pixels[50:138, 158:228] = 205  # the third room never entered: unknown behind its door
    plan = ksmcmc.floorplan(pixels, resolution=0.05, iterations=ITERATIONS)
    assert plan.placeholders == plan.world["placeholders"]
    assert plan.placeholders, "the unseen room's doorway is a frontier"
    for p in plan.placeholders:
        assert pixels[p["y"], p["x"]] == 254, p
        assert 0.0 <= p["p_new_room"] <= 1.0
        assert math.isclose(sum(p["types"].values()), 1.0, abs_tol=0.01)
    # One stands in that room's doorway (columns 183 - 203, row 48 - 49), within 1 m.
    assert any(abs(p["x"] - 193) <= 20 and abs(p["y"] - 49) <= 20 for p in plan.placeholders)
    # The fully seen office has none inside its walls.
    seen = ksmcmc.floorplan(drawn_office(), resolution=0.05, iterations=ITERATIONS)
    assert all(not (10 <= p["y"] < 140 and 10 <= p["x"] < 230) for p in seen.placeholders)


def test_a_uint8_array_is_the_image_of_the_same_pixels():
    pixels = drawn_office()
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "office.pgm")
        with open(path, "wb") as f:
            f.write(b"P5\n%d %d\n255\n" % (pixels.shape[1], pixels.shape[0]) + pixels.tobytes())
        from_file = ksmcmc.floorplan(path, resolution=0.05, iterations=ITERATIONS)
    from_array = ksmcmc.floorplan(pixels, resolution=0.05, iterations=ITERATIONS)
    assert np.array_equal(from_file.labels, from_array.labels)


def test_resolution_is_metres_and_changes_the_areas():
    pixels = drawn_office()
    fine = ksmcmc.floorplan(pixels, resolution=0.05, iterations=ITERATIONS)
    with pytest.warns(UserWarning, match="0.05 m"):
        default = ksmcmc.floorplan(pixels, iterations=ITERATIONS)
    assert np.array_equal(fine.labels, default.labels)
    area = sum(r["area_m2"] for r in fine.rooms)
    free = int((pixels == 254).sum())
    assert math.isclose(area, free * 0.05 * 0.05, rel_tol=0.1), (area, free)


@pytest.mark.parametrize(
    "bad, message",
    [
        (np.zeros((0, 5), dtype=np.uint8), "2-D array with cells"),
        (np.zeros((4, 4, 3), dtype=np.uint8), "2-D array"),
        (np.zeros(16, dtype=np.uint8), "2-D array"),
        (np.zeros((20, 20), dtype=np.float32), "dtype is float32"),
        (np.zeros((20, 20), dtype=np.uint16), "dtype is uint16"),
        (np.full((20, 20), 101, dtype=np.int8), "occupancy value 101"),
        (np.full((20, 20), -5, dtype=np.int8), "occupancy value -5"),
        ([[0, 254], [254, 0]], "path or a 2-D numpy array"),
    ],
)
def test_bad_arrays_are_refused_with_a_message(bad, message):
    with pytest.raises(ValueError, match=message):
        ksmcmc.floorplan(bad, resolution=0.05, iterations=10)


def test_bad_settings_are_refused_with_a_message():
    pixels = drawn_office()
    with pytest.raises(ValueError, match="needs resolution"):
        ksmcmc.floorplan(as_occupancy(pixels))
    for r in (0.0, -1.0, float("nan"), 11.0):
        with pytest.raises(ValueError, match="resolution must be"):
            ksmcmc.floorplan(pixels, resolution=r, iterations=10)
    with pytest.raises(ValueError, match="seed must be"):
        ksmcmc.floorplan(pixels, resolution=0.05, seed=-1)
    with pytest.raises(ValueError, match="edits"):
        ksmcmc.floorplan(pixels, resolution=0.05, iterations=10, edits="not json")
    with pytest.raises(ValueError, match="origin must be"):
        ksmcmc.floorplan(pixels, resolution=0.05, origin=(1.0, 2.0), iterations=10)
    with pytest.raises(OSError):
        ksmcmc.floorplan(os.path.join(REPO, "no-such-map.pgm"))
    with pytest.raises(OSError):
        ksmcmc.floorplan(pixels, resolution=0.05, iterations=10, knowledge="/no/such/rules.mln")


def test_knowledge_names_read_as_the_command_line_reads_them(tmp_path):
    pixels = drawn_office()
    broken = tmp_path / "broken.mln"
    broken.write_text("Room(unit\n")
    # Rules that do not parse are refused with the file's name and the place, before any chain runs.
    with pytest.raises(ValueError, match=r"broken\.mln: line 1"):
        ksmcmc.floorplan(pixels, resolution=0.05, iterations=10, knowledge=str(broken))
    # The hand-set weights and the weak prior are names, not files.
    for name in ["handset", "none"]:
        plan = ksmcmc.floorplan(pixels, resolution=0.05, iterations=200, knowledge=name)
        assert plan.report["iterations"] == 200
        assert plan.report["knowledge"] == (name != "none"), name


def test_the_exports_are_the_command_lines_files():
    plan = ksmcmc.floorplan(drawn_office(), resolution=0.05, iterations=ITERATIONS)
    assert plan.png().startswith(b"\x89PNG\r\n\x1a\n")
    assert plan.glb().startswith(b"glTF")
    assert plan.svg().lstrip().startswith("<svg") or "<svg" in plan.svg()[:200]
    geo = json.loads(plan.geojson())
    assert geo["type"] == "FeatureCollection" and geo["features"]
    placed = json.loads(plan.geojson("48.1,11.6,0"))
    assert placed != geo
    with pytest.raises(ValueError, match="georef"):
        plan.geojson("north pole")
    assert plan.report["rooms"] == len(plan.rooms)
    assert plan.graph, plan.graph
    with tempfile.TemporaryDirectory() as d:
        names = sorted(os.path.basename(p) for p in plan.save(d))
        assert names == sorted(
            ["world.json", "overlay.png", "graph.json", "trace.csv", "labels.pgm", "report.json",
             "world.geojson", "world.svg", "world.glb"]
        )
        assert np.array_equal(read_pgm16(os.path.join(d, "labels.pgm")), plan.labels)


def test_a_route_crosses_the_door_between_corridor_and_room():
    plan = ksmcmc.floorplan(drawn_office(), resolution=0.05, iterations=ITERATIONS)
    route = plan.route((120, 30), (47, 120))
    corridor, room = int(plan.labels[30, 120]), int(plan.labels[120, 47])
    assert route["rooms"][0] == corridor and route["rooms"][-1] == room, route["rooms"]
    assert route["path"][0] == [120, 30] and route["path"][-1] == [47, 120]
    # Through the door (1 m wide at row 48 - 49, columns 37 - 56): at least the straight
    # distance, and not much more.
    assert any(48 <= y <= 49 and 37 <= x <= 56 for x, y in route["path"]), route["path"]
    straight = math.hypot(120 - 47, 30 - 120) * 0.05
    assert straight <= route["length_m"] <= 1.5 * straight, route["length_m"]
    with pytest.raises(ValueError):
        plan.route((5, 5), (47, 120))  # outside the building: no room there
    with pytest.raises(ValueError, match="start must be"):
        plan.route("here", (47, 120))


def test_the_chain_runs_without_the_gil():
    # While one thread explains a map, another thread keeps running Python.
    ticks = []
    done = threading.Event()

    def tick():
        while not done.is_set():
            ticks.append(1)
            done.wait(0.001)

    t = threading.Thread(target=tick)
    t.start()
    try:
        ksmcmc.floorplan(drawn_office(), resolution=0.05, iterations=20000)
    finally:
        done.set()
        t.join()
    assert len(ticks) > 10, len(ticks)


def test_mln_query_matches_the_exact_marginal():
    # One soft rule w: Smokes(x) => Cancer(x) with Smokes(Anna) given: P(Cancer(Anna)) is
    # e^w / (1 + e^w) exactly (the rule's only world where it is false has Cancer false).
    w = 1.5
    rules = f"Smokes(person)\nCancer(person)\n{w} Smokes(x) => Cancer(x)\n"
    p = mln.query(rules, "Smokes(Anna)\n", ["Cancer"])
    exact = math.exp(w) / (1 + math.exp(w))
    assert abs(p["Cancer(Anna)"] - exact) < 0.03, (p, exact)
    with pytest.raises(ValueError, match="line"):
        mln.query("Smokes(person\n", "", ["Smokes"])
    with pytest.raises(ValueError, match="predicates to query"):
        mln.query(rules, "", [])


def test_mln_learn_moves_the_weight_toward_the_data():
    rules = "Smokes(person)\nCancer(person)\n0 Smokes(x) => Cancer(x)\n"
    people = ["A", "B", "C", "D"]
    db = "".join(f"Smokes({p})\nCancer({p})\n" for p in people)
    learned = mln.learn(rules, [db])
    line = next(l for l in learned.splitlines() if "Smokes(x) => Cancer(x)" in l and not l.startswith("//"))
    weight = float(line.split()[0])
    assert weight > 0.5, learned
    with pytest.raises(ValueError, match="database"):
        mln.learn(rules, ["Smokes(A\n"])


def test_the_readme_example_runs_as_written():
    # python/README.md's first python block (README.md carries the same block, tests/it/readme.rs
    # checks), run from the repository root as the README says.
    with open(os.path.join(REPO, "python", "README.md")) as f:
        text = f.read()
    start = text.index("```python\n") + len("```python\n")
    code = text[start : text.index("```", start)]
    here = os.getcwd()
    os.chdir(REPO)
    try:
        scope = {}
        exec(compile(code, "python/README.md", "exec"), scope)
    finally:
        os.chdir(here)
    plan = scope["plan"]
    assert len(plan.rooms) >= 3
    assert os.path.exists(os.path.join(REPO, "out", "plan", "labels.pgm"))
