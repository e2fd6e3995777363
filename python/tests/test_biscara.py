"""The package against the command line on the bundled data, its errors, its argument checks,
and the GIL released during long calls."""

import csv
import io
import json
import os
import re
import signal
import threading
import time

import numpy as np
import pytest

import biscara

from conftest import ROOT


def read_csv(text):
    """A CSV's columns as float arrays (non-numeric columns kept as strings)."""
    rows = list(csv.reader(io.StringIO(text)))
    header, body = rows[0], rows[1:]
    columns = {}
    for k, name in enumerate(header):
        values = [row[k] for row in body]
        try:
            columns[name] = np.array([float(v) if v != "" else np.nan for v in values])
        except ValueError:
            columns[name] = np.array(values)
    return columns


def cli_error(done):
    """The command line's error message without its prefix."""
    lines = [l for l in done.stderr.splitlines() if l.startswith("biscara: error: ")]
    assert lines, done.stderr
    start = done.stderr.index("biscara: error: ") + len("biscara: error: ")
    return done.stderr[start:].rstrip("\n")


# ---- the package -----------------------------------------------------------------------------


def test_version_is_the_workspace_version():
    text = (ROOT / "Cargo.toml").read_text()
    section = text[text.index("[workspace.package]"):]
    version = re.search(r'^version = "([^"]+)"', section, re.M).group(1)
    assert biscara.__version__ == version


def test_error_is_one_exception_class():
    assert issubclass(biscara.Error, Exception)
    assert biscara.Error.__module__ == "biscara"


# ---- robot -----------------------------------------------------------------------------------


def test_robot_json_round_trip(cli, data):
    robot = biscara.Robot()
    assert json.loads(robot.to_json()) == json.loads(cli("robot").stdout)
    path = data / "robots" / "asymmetric.json"
    asymmetric = biscara.Robot.from_file(path)
    assert json.loads(asymmetric.to_json()) == json.loads(cli("--robot", path, "robot").stdout)
    again = biscara.Robot.from_json(asymmetric.to_json())
    assert again.to_json() == asymmetric.to_json()
    assert again.name == asymmetric.name


def test_robot_file_errors_have_path_line_and_column(cli, tmp_path):
    bad = tmp_path / "robot.json"
    bad.write_text('{\n  "name": "x",\n  "links": {"l1": "long"}\n}\n')
    with pytest.raises(biscara.Error) as caught:
        biscara.Robot.from_file(bad)
    err = caught.value
    assert err.path == str(bad)
    assert err.line == 3
    assert err.column is not None
    assert str(err) == cli_error(cli("--robot", bad, "robot", check=False))
    with pytest.raises(biscara.Error) as caught:
        biscara.Robot.from_json('{"name": 3}')
    assert caught.value.path is None and caught.value.line == 1
    with pytest.raises(biscara.Error) as caught:
        biscara.Robot.from_file(tmp_path / "missing.json")
    assert caught.value.path == str(tmp_path / "missing.json")
    assert caught.value.line is None


# ---- ik / fk ---------------------------------------------------------------------------------

POSES = np.array(
    [[0, 400, 50, 0], [150, 320, 10, 30], [-150, 300, 20, 0], [100, 250, 0, -45], [-60, 380, 80, 170]],
    dtype=float,
)


def test_ik_and_fk_match_the_command_line(cli):
    robot = biscara.Robot()
    joints = robot.ik(POSES)
    assert joints.shape == (len(POSES), 4) and joints.dtype == np.float64
    for pose, q in zip(POSES, joints):
        expected = json.loads(cli("ik", "--json", "--", *pose).stdout)
        np.testing.assert_allclose(
            q, [expected["theta1"], expected["theta2"], expected["theta3"], expected["d4"]],
            rtol=0, atol=1e-9,
        )
        pose_back = json.loads(cli("fk", "--json", "--", *q).stdout)
        got = robot.fk(q[None, :])[0]
        np.testing.assert_allclose(got[:3], pose_back["pose"][:3] if "pose" in pose_back else
                                   [pose_back["x"], pose_back["y"], pose_back["z"]], atol=1e-9)
    np.testing.assert_allclose(robot.fk(joints), POSES, atol=1e-9)


def test_ik_radians():
    robot = biscara.Robot()
    poses = POSES.copy()
    poses[:, 3] = np.radians(poses[:, 3])
    q_rad = robot.ik(poses, angle_unit="rad")
    q_deg = robot.ik(POSES)
    np.testing.assert_allclose(np.degrees(q_rad[:, :3]), q_deg[:, :3], atol=1e-9)
    np.testing.assert_allclose(q_rad[:, 3], q_deg[:, 3])
    np.testing.assert_allclose(robot.fk(q_rad, angle_unit="rad"), poses, atol=1e-9)


def test_ik_batch_path_on_many_poses_equals_one_by_one():
    robot = biscara.Robot()
    rng = np.random.default_rng(7)
    poses = np.column_stack([
        rng.uniform(-200, 200, 100_000), rng.uniform(150, 420, 100_000),
        rng.uniform(0, 100, 100_000), rng.uniform(-180, 180, 100_000),
    ])
    joints, mask = robot.ik(poses, errors="nan")
    assert mask.dtype == np.bool_ and 0 < mask.sum() < len(mask)
    assert np.isnan(joints[~mask]).all() and np.isfinite(joints[mask]).all()
    sample = np.flatnonzero(mask)[:50]
    for k in sample:
        np.testing.assert_array_equal(robot.ik(poses[k:k + 1])[0], joints[k])


def test_ik_unreachable_names_the_row(cli):
    robot = biscara.Robot()
    poses = np.vstack([POSES, [[1000, 0, 0, 0]], POSES])
    with pytest.raises(biscara.Error) as caught:
        robot.ik(poses)
    message = str(caught.value)
    assert message.startswith(f"row {len(POSES)}: ")
    cli_message = cli_error(cli("ik", "1000", "0", "0", "0", check=False))
    assert message.endswith(cli_message.split("is unreachable", 1)[1])
    assert caught.value.path is None and caught.value.line is None
    joints, mask = robot.ik(poses, errors="nan")
    assert mask.tolist() == [True] * len(POSES) + [False] + [True] * len(POSES)
    assert np.isnan(joints[len(POSES)]).all()


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_ik_refuses_non_finite_poses(bad):
    poses = POSES.copy()
    poses[2, 1] = bad
    with pytest.raises(ValueError, match=r"poses: row 2"):
        biscara.Robot().ik(poses)
    with pytest.raises(ValueError, match=r"joints: row 2"):
        biscara.Robot().fk(poses)


def test_ik_refuses_wrong_shapes_and_dtypes():
    robot = biscara.Robot()
    for shape in [(4,), (3, 3), (2, 5), (2, 4, 1)]:
        with pytest.raises(ValueError, match="poses must have shape"):
            robot.ik(np.zeros(shape))
    with pytest.raises(TypeError, match="poses"):
        robot.ik(np.array([["a", "b", "c", "d"]]))
    with pytest.raises(TypeError, match="poses"):
        robot.ik(POSES.astype(complex))
    with pytest.raises(TypeError, match="joints"):
        robot.fk(np.array([[None, 1, 2, 3]], dtype=object))
    with pytest.raises(ValueError, match="angle_unit"):
        robot.ik(POSES, angle_unit="grad")
    with pytest.raises(ValueError, match="errors"):
        robot.ik(POSES, errors="ignore")
    # Integers, lists and non-contiguous arrays are converted.
    np.testing.assert_array_equal(robot.ik(POSES.astype(int).tolist()), robot.ik(POSES.astype(int)))
    wide = np.zeros((len(POSES), 8))
    wide[:, ::2] = POSES
    np.testing.assert_array_equal(robot.ik(wide[:, ::2]), robot.ik(POSES))
    assert robot.ik(np.zeros((0, 4))).shape == (0, 4)


def test_workspace_matches_the_command_line(cli):
    for step in (2.0, 5.0):
        got = biscara.Robot().workspace(step=step)
        expected = json.loads(cli("workspace", "--step", step, "--json").stdout)
        assert got["area_mm2"] == pytest.approx(expected["area_mm2"])
        assert got["step_mm"] == expected["step_mm"]
        r = expected["rectangle"]
        assert got["rect"] == (r["min"][0], r["max"][0], r["min"][1], r["max"][1])
        grid = read_csv(cli("workspace", "--step", step, "--csv").stdout)
        reachable = {(x, y) for x, y, ok in zip(grid["x_mm"], grid["y_mm"], grid["reachable"]) if ok}
        ys, xs = np.nonzero(got["grid"])
        mine = {(got["x_mm"][i], got["y_mm"][j]) for j, i in zip(ys, xs)}
        assert mine == reachable
        assert got["grid"].sum() * step * step == pytest.approx(got["area_mm2"])
    with pytest.raises(ValueError, match="step"):
        biscara.Robot().workspace(step=float("nan"))


# ---- programs --------------------------------------------------------------------------------

PROGRAMS = [
    ("arcs_and_offsets.ngc", []),
    ("pick_place_inch.ngc", []),
    ("laser_engraving.ngc", ["--fit"]),
    ("print_square.gcode", ["--fit"]),
]


def kwargs_of(flags):
    return {"fit": True} if "--fit" in flags else {}


@pytest.mark.parametrize("name,flags", PROGRAMS)
def test_interpret_matches_the_command_line(cli, data, name, flags):
    path = data / "programs" / name
    expected = [json.loads(line) for line in cli("interpret", *flags, path).stdout.splitlines()]
    got = biscara.interpret(path, **kwargs_of(flags))
    assert got == expected
    assert biscara.interpret(source=path.read_text(), **kwargs_of(flags)) == expected


@pytest.mark.parametrize("name,flags", PROGRAMS)
def test_joints_match_the_command_line(cli, data, name, flags):
    path = data / "programs" / name
    for extra, kwargs in [
        ([], {}),
        (["--derivatives", "--angle-unit", "deg", "--events"], {"derivatives": True, "angle_unit": "deg", "events": True}),
    ]:
        expected = read_csv(cli("joints", *flags, *extra, path).stdout)
        got = biscara.joints(path, **kwargs_of(flags), **kwargs)
        assert list(got) == list(expected)
        for column, values in expected.items():
            assert got[column].dtype == np.float64
            np.testing.assert_allclose(got[column], values, rtol=0, atol=5.1e-7, err_msg=column)


@pytest.mark.parametrize("robot_name", ["small-motors.json", "servo-example.json"])
def test_joints_torques_match_the_command_line(cli, data, robot_name):
    path = data / "programs" / "pick_place_inch.ngc"
    robot_path = data / "robots" / robot_name
    expected = read_csv(cli("--robot", robot_path, "joints", "--torques", path).stdout)
    assert "tau_theta1_Nm" in expected and "payload_kg" in expected
    robot = biscara.Robot.from_file(robot_path)
    got = biscara.joints(path, robot=robot, torques=True)
    assert list(got) == list(expected)
    for column, values in expected.items():
        np.testing.assert_allclose(got[column], values, rtol=0, atol=5.1e-7, err_msg=column)
    # The payload is held from each pick to its place, and only then.
    assert got["payload_kg"].max() > 0 and got["payload_kg"].min() == 0


def test_design_by_adept_cycle(cli, data, tmp_path):
    out = tmp_path / "designs.csv"
    robot_path = data / "robots" / "small-motors.json"
    cli("--robot", robot_path, "design", "--l1", "200:220:2", "--l2", "260:280:2", "--base",
        "200:200:1", "--objective", "cycle", "-o", out)
    expected = read_csv(out.read_text())
    got = biscara.design(l1=(200, 220, 2), l2=(260, 280, 2), base=(200, 200, 1),
                         objective="cycle", robot=biscara.Robot.from_file(robot_path))
    np.testing.assert_allclose(got["cycle_s"], expected["cycle_s"], rtol=0, atol=5.1e-4)
    best = got["best"]
    assert best is not None
    ok = got["status"] == "ok"
    assert got["cycle_s"][best] == np.nanmin(got["cycle_s"][ok])


def test_joints_stop_at_the_time_limit():
    endless = "G21 G90\nO1 while [1]\nG1 X10 Y400 F6000\nG1 X-10 Y380\n#1 = [#1 + 1]\nO1 endwhile\nM2\n"
    with pytest.raises(biscara.Error, match="time.limit"):
        biscara.joints(source=endless, time_limit=2.0)


def test_joints_options_reach_the_pipeline(cli, data):
    path = data / "programs" / "arcs_and_offsets.ngc"
    flags = ["--profile", "trapezoid", "--dt", "0.004", "--origin", "10,20,0,0"]
    expected = read_csv(cli("joints", *flags, path).stdout)
    got = biscara.joints(path, profile="trapezoid", dt=0.004, origin=(10, 20, 0, 0))
    assert len(got["t_s"]) == len(expected["t_s"])
    for column, values in expected.items():
        np.testing.assert_allclose(got[column], values, rtol=0, atol=5.1e-7, err_msg=column)
    robot_path = data / "robots" / "asymmetric.json"
    expected = read_csv(cli("--robot", robot_path, "joints", "--fit", path).stdout)
    got = biscara.joints(path, robot=biscara.Robot.from_file(robot_path), fit=True)
    np.testing.assert_allclose(got["theta1_rad"], expected["theta1_rad"], atol=5.1e-7)


@pytest.mark.parametrize("name,flags", PROGRAMS[:3])
def test_interpolate_matches_the_command_line(cli, data, name, flags):
    path = data / "programs" / name
    for extra, kwargs in [([], {}), (["--events"], {"events": True})]:
        expected = read_csv(cli("interpolate", *flags, *extra, path).stdout)
        got = biscara.interpolate(path, **kwargs_of(flags), **kwargs)
        assert list(got) == list(expected)
        for column, values in expected.items():
            np.testing.assert_allclose(got[column], values, rtol=0, atol=5.1e-7, err_msg=column)


@pytest.mark.parametrize(
    "name,scene", [("pen_plot.ngc", None), ("arcs_and_offsets.ngc", "cell_with_post.json")]
)
def test_check_matches_the_command_line(cli, data, name, scene):
    path = data / "programs" / name
    flags = [] if scene is None else ["--scene", data / "scenes" / scene]
    expected = json.loads(cli("check", "--json", *flags, path, check=False).stdout)
    got = biscara.check(path, scene=None if scene is None else data / "scenes" / scene)
    assert got == expected
    if scene is not None:
        as_dict = json.loads((data / "scenes" / scene).read_text())
        assert biscara.check(source=path.read_text(), scene=as_dict) == expected


def test_check_stops_an_endless_program_at_the_time_limit(cli, tmp_path):
    program = tmp_path / "endless.ngc"
    program.write_text(
        "G21 G90 F6000\nG0 X0 Y300\no100 while [1]\nG1 X50\nG1 X0\no100 endwhile\nM2\n"
    )
    with pytest.raises(biscara.Error) as caught:
        biscara.check(program, time_limit=2.0)
    # The command line's message, naming the keyword instead of the flag --time-limit.
    expected = cli_error(cli("check", "--time-limit", "2", program, check=False))
    assert str(caught.value).split(", past")[0] == expected.split(", past")[0]
    assert "past the time limit" in str(caught.value)
    assert "(a larger time_limit allows more" in str(caught.value)
    assert caught.value.path == str(program) and caught.value.line in (4, 5)
    with pytest.raises(ValueError, match="time_limit"):
        biscara.check(program, time_limit=-1)


def test_design_matches_the_command_line(cli):
    args = ["--l1", "150:270:3", "--l2", "210:330:3", "--base", "100:300:3", "--step", "5"]
    done = cli("design", *args, "--task", "-100,250,100,350", "--objective", "gci")
    expected = read_csv(done.stdout)
    got = biscara.design(
        l1=(150, 270, 3), l2=(210, 330, 3), base=(100, 300, 3), step=5,
        task=(-100, 250, 100, 350), objective="gci",
    )
    for column, values in expected.items():
        if values.dtype.kind == "f":
            decimals = 6 if column in ("gci", "lci_min") else 3
            np.testing.assert_allclose(got[column], values, atol=0.51 * 10**-decimals, err_msg=column)
        else:
            assert got[column].tolist() == values.tolist()
    best = got["best"]
    note = re.search(r"l1 = (\S+) mm, l2 = (\S+) mm, base = (\S+) mm", done.stderr)
    assert (got["l1"][best], got["l2"][best], got["base"][best]) == tuple(map(float, note.groups()))
    chosen = biscara.Robot().with_design(got["l1"][best], got["l2"][best], got["base"][best])
    assert json.loads(chosen.to_json())["links"]["l1"] == got["l1"][best]


def test_design_times_programs_as_the_command_line(cli, data):
    program = data / "programs" / "arcs_and_offsets.ngc"
    args = ["--l1", "190:230:2", "--l2", "250:290:2", "--base", "200:200:1", "--step", "10"]
    done = cli("design", *args, "--programs", program, "--objective", "time")
    expected = read_csv(done.stdout)
    got = biscara.design(
        l1=(190, 230, 2), l2=(250, 290, 2), base=(200, 200, 1), step=10,
        programs=[program], objective="time",
    )
    np.testing.assert_allclose(got["time_s"], expected["time_s"], atol=0.00051)
    assert np.isfinite(got["time_s"]).any()
    with pytest.raises(ValueError, match="programs"):
        biscara.design(l1=(190, 230, 2), l2=(250, 290, 2), base=(200, 200, 1), objective="time")


def test_design_refuses_bad_ranges():
    with pytest.raises(ValueError, match="l1"):
        biscara.design(l1=(150, 300), l2=(200, 350, 7), base=(100, 300, 5))
    with pytest.raises(ValueError, match="base"):
        biscara.design(l1=(150, 300, 2), l2=(200, 350, 2), base=(100, float("nan"), 5))
    with pytest.raises(TypeError, match="l2"):
        biscara.design(l1=(150, 300, 2), l2="200:350:2", base=(100, 300, 5))


def test_gen_and_post_match_the_command_line(cli, data):
    for name in ("pick_place.txt", "pallet_3x3.txt"):
        path = data / "jobs" / name
        expected = cli("gen", path).stdout
        assert biscara.gen(path) == expected
        assert biscara.gen(source=path.read_text()) == expected
        assert biscara.gen(path, line_numbers=True) == cli("gen", "--line-numbers", path).stdout
    cl = data / "cl" / "bracket.cl"
    expected = cli("post", cl).stdout
    assert biscara.post(cl.read_text()) == expected
    assert biscara.post(path=cl) == expected


# ---- errors ----------------------------------------------------------------------------------


def test_program_errors_have_path_line_and_column(cli, tmp_path):
    bad = tmp_path / "bad.ngc"
    # Ended by M2: LinuxCNC's program without a doubt, so the message carries no note on the
    # dialect (whose hint is worded for `--dialect` there, for the `dialect` argument here).
    bad.write_text("G21 G90\nG1 X0 Y300 F1000\nG1 X10 Q5 Y300\nM2\n")
    for function in (biscara.interpret, biscara.joints, biscara.interpolate, biscara.check):
        with pytest.raises(biscara.Error) as caught:
            function(bad)
        err = caught.value
        assert (err.path, err.line) == (str(bad), 3)
        assert err.column is not None
    expected = cli_error(cli("joints", bad, check=False))
    with pytest.raises(biscara.Error) as caught:
        biscara.joints(bad)
    assert str(caught.value) == expected
    with pytest.raises(biscara.Error) as caught:
        biscara.joints(source=bad.read_text())
    assert caught.value.path is None and caught.value.line == 3
    assert str(caught.value).startswith("<source>:3:")


def test_unreachable_sample_error_matches_the_command_line(cli, data):
    path = data / "programs" / "pen_plot.ngc"
    with pytest.raises(biscara.Error) as caught:
        biscara.joints(path)
    assert str(caught.value) == cli_error(cli("joints", path, check=False))
    assert caught.value.path == str(path) and caught.value.line == 6


def test_points_and_cl_errors_are_located(cli, tmp_path):
    points = tmp_path / "points.txt"
    points.write_text("home 0 400 100 0\nnot a point\n")
    with pytest.raises(biscara.Error) as caught:
        biscara.gen(points)
    assert (caught.value.path, caught.value.line) == (str(points), 2)
    assert str(caught.value) == cli_error(cli("gen", points, check=False))
    cl = tmp_path / "job.cl"
    cl.write_text("RAPID\nGOTO/0,400,50\nFROBNICATE/1\n")
    with pytest.raises(biscara.Error) as caught:
        biscara.post(path=cl)
    assert (caught.value.path, caught.value.line) == (str(cl), 3)
    assert str(caught.value) == cli_error(cli("post", cl, check=False))
    with pytest.raises(biscara.Error) as caught:
        biscara.post(cl.read_text())
    assert caught.value.path is None and caught.value.line == 3


def test_inputs_of_other_kinds(cli, data, tmp_path):
    program = data / "programs" / "arcs_and_offsets.ngc"
    motions = tmp_path / "job.jsonl"
    motions.write_text(cli("interpret", program).stdout)
    expected = read_csv(cli("joints", motions).stdout)
    got = biscara.joints(motions)
    np.testing.assert_allclose(got["theta2_rad"], expected["theta2_rad"], atol=5.1e-7)
    path_csv = tmp_path / "path.csv"
    path_csv.write_text(cli("interpolate", program).stdout)
    expected = read_csv(cli("joints", path_csv).stdout)
    got = biscara.joints(source=path_csv.read_text(), kind="path")
    np.testing.assert_allclose(got["d4_mm"], expected["d4_mm"], atol=5.1e-7)
    with pytest.raises(biscara.Error) as caught:
        biscara.interpolate(path_csv)
    assert str(caught.value) == cli_error(cli("interpolate", path_csv, check=False))
    assert caught.value.path == str(path_csv)
    with pytest.raises(ValueError, match="kind"):
        biscara.joints(path_csv, kind="csv")


def test_missing_file_and_bad_scene(tmp_path, data):
    with pytest.raises(biscara.Error) as caught:
        biscara.joints(tmp_path / "missing.ngc")
    assert caught.value.path == str(tmp_path / "missing.ngc") and caught.value.line is None
    scene = tmp_path / "scene.json"
    scene.write_text('{"boxes": [\n {"name": "a", "min": [0, 0], "max": [1, 1, 1]}]}')
    with pytest.raises(biscara.Error) as caught:
        biscara.check(data / "programs" / "arcs_and_offsets.ngc", scene=scene)
    assert (caught.value.path, caught.value.line) == (str(scene), 2)


def test_program_arguments_are_checked(data):
    path = data / "programs" / "arcs_and_offsets.ngc"
    with pytest.raises(TypeError, match="exactly one"):
        biscara.joints()
    with pytest.raises(TypeError, match="exactly one"):
        biscara.joints(path, source="G0 X0")
    with pytest.raises(ValueError, match="dt"):
        biscara.joints(path, dt=0.0)
    with pytest.raises(ValueError, match="dt"):
        biscara.joints(path, dt=float("nan"))
    with pytest.raises(TypeError, match="dt"):
        biscara.joints(path, dt="fast")
    with pytest.raises(ValueError, match="origin"):
        biscara.joints(path, origin=(0, 0, float("inf"), 0))
    with pytest.raises(ValueError, match="origin"):
        biscara.joints(path, origin=(0, 0, 0))
    with pytest.raises(ValueError, match="profile"):
        biscara.joints(path, profile="fastest")
    with pytest.raises(ValueError, match="angle_unit"):
        biscara.joints(path, angle_unit="grad")
    with pytest.raises(TypeError, match="robot"):
        biscara.joints(path, robot="robot.json")
    with pytest.raises(ValueError, match="dialect"):
        biscara.joints(path, dialect="heidenhain")
    with pytest.raises(ValueError, match="tool"):
        biscara.interpret(path, tool="welder")
    with pytest.raises(TypeError, match="unexpected keyword"):
        biscara.joints(path, colour="red")


# ---- the GIL and Ctrl-C ----------------------------------------------------------------------


def long_program(moves=1000):
    lines = ["G21 G90 G94 F6000", "G0 X-100 Y250 Z20"]
    for k in range(moves):
        lines.append(f"G1 X{100 if k % 2 == 0 else -100} Y{250 + (k % 100)}")
    lines.append("M2")
    return "\n".join(lines) + "\n"


def counting_during(call):
    """How fast a pure-Python thread counts while `call` runs, as a fraction of how fast it counts
    alone (while the main thread sleeps), and how long the call took."""
    done = threading.Event()
    stamps = []

    def count():
        n = 0
        while not done.is_set():
            n += 1
            if n % 1000 == 0:
                stamps.append(time.perf_counter())

    thread = threading.Thread(target=count)
    thread.start()
    try:
        alone = time.perf_counter()
        time.sleep(0.2)
        start = time.perf_counter()
        call()
        end = time.perf_counter()
    finally:
        done.set()
        thread.join()
    rate = sum(1 for t in stamps if alone < t < start) / (start - alone)
    during = sum(1 for t in stamps if start < t < end)
    return during / (rate * (end - start)), end - start


def test_joints_releases_the_gil():
    program = long_program()
    trajectory = {}
    fraction, seconds = counting_during(lambda: trajectory.update(biscara.joints(source=program)))
    assert len(trajectory["t_s"]) > 1_000_000
    # Holding the GIL, the call would leave the counting thread only the switch intervals at
    # its edges (a few ms: about 1 % of a call this long, measured with `sum(range(…))`).
    assert seconds > 0.1
    assert fraction > 0.1, (fraction, seconds)


def test_ctrl_c_interrupts_a_long_call():
    program = long_program(5_000)
    main = threading.main_thread().ident
    timer = threading.Timer(0.3, lambda: signal.pthread_kill(main, signal.SIGINT))
    timer.start()
    start = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        biscara.joints(source=program)
    timer.join()
    assert time.perf_counter() - start < 30
