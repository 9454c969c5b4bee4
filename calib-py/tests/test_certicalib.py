"""The Python package against the gough CLI: same results from files and from numpy arrays,
ValueError naming file/line/field on bad input, outliers named, the JSON report's structure."""

import json
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import certicalib
from cli_binaries import REPO, repo_binary



@pytest.fixture(scope="module")
def data(tmp_path_factory) -> Path:
    d = tmp_path_factory.mktemp("sim")
    truth = certicalib.simulate(d, configs=21, seed=7, outliers=[(5, 2, 0.3)])
    assert truth["outliers"] == [{"config": 5, "leg": 2, "delta": 0.3}]
    return d


def files(d: Path):
    return d / "robot.toml", d / "measurements.csv", d / "uncertainty.toml"


def cli_report(d: Path, *extra: str) -> dict:
    out = d / "cli.json"
    robot, meas, unc = files(d)
    subprocess.run([str(repo_binary("gough")), "certify", "--robot", str(robot), "--measurements",
                    str(meas), "--uncertainty", str(unc), "--json", str(out), *extra],
                   check=False, capture_output=True)
    return json.loads(out.read_text())


def same_legs(a: dict, b: dict) -> None:
    assert len(a["legs"]) == len(b["legs"])
    for x, y in zip(a["legs"], b["legs"]):
        for key in ("leg", "status", "names", "x0", "x1", "x2", "outer", "inner", "witness",
                    "conflict", "outliers", "converged", "iterations", "boxes"):
            assert x[key] == y[key], f"leg {x['leg']}: {key}"


def test_files_give_the_same_report_as_the_cli(data):
    report = certicalib.certify(*files(data))
    cli = cli_report(data)
    same_legs(report.to_dict(), cli)
    assert set(report.to_dict()) == set(cli) and report.to_dict()["version"] == 1
    leg1, leg2 = report.legs[0], report.legs[1]
    assert leg1.status == "consistent" and leg2.status == "empty"
    assert leg1.outer.shape == (7, 2) and leg1.outer.dtype == np.float64
    assert leg1.inner.shape == (7, 2) and leg1.x1.shape == (7, 2) and leg1.witness.shape == (7,)
    assert leg1.names == certicalib.PARAMETER_NAMES
    assert np.all(leg1.outer[:, 0] <= leg1.inner[:, 0]) and np.all(leg1.inner[:, 1] <= leg1.outer[:, 1])
    assert np.all(leg1.ratio <= 1.05 + 1e-9)
    assert leg2.outer is None and 5 in leg2.conflict
    # json.dumps of to_dict writes the JSON report: it reads back identical.
    assert json.loads(json.dumps(report.to_dict())) == report.to_dict()


def test_sweep_fast_and_paths_as_pathlike(data):
    robot, meas, unc = files(data)
    report = certicalib.certify(robot, str(meas), unc, legs=[1], sweep=True, fast=True)
    same_legs(report.to_dict(), cli_report(data, "--legs", "1", "--sweep", "--fast"))
    leg = report.legs[0]
    assert leg.x2.shape == (7, 2) and leg.converged is None
    assert np.array_equal(leg.outer, leg.x1)


def read_uncertainty(path: Path) -> dict:
    values = {}
    for line in path.read_text().splitlines():
        if "=" in line and not line.lstrip().startswith("#"):
            key, value = line.split("=")
            values[key.strip()] = float(value)
    return values


def test_numpy_arrays_give_the_same_results_as_files(data):
    truth = json.loads((data / "truth.json").read_text())
    nominal = truth["nominal"]
    robot = {"a": np.array([leg["a"] for leg in nominal]),
             "b": np.array([leg["b"] for leg in nominal]),
             "l": np.array([leg["l"] for leg in nominal]), "radius": 0.1}
    rows = np.loadtxt(data / "measurements.csv", delimiter=",", skiprows=1)
    u = read_uncertainty(data / "uncertainty.toml")
    from_arrays = certicalib.certify(robot, rows, u, legs=[1, 3])
    from_files = certicalib.certify(*files(data), legs=[1, 3])
    same_legs(from_arrays.to_dict(), from_files.to_dict())
    as_dict = {"p": rows[:, 0:3], "axis": rows[:, 3:6], "angle_deg": rows[:, 6],
               "lengths": rows[:, 7:]}
    same_legs(certicalib.certify(robot, as_dict, u, legs=[1, 3]).to_dict(), from_files.to_dict())


def test_outliers_are_named_and_tolerated(data):
    strict = certicalib.certify(*files(data), legs=[2])
    assert strict.legs[0].status == "empty" and 5 in strict.legs[0].conflict
    tolerant = certicalib.certify(*files(data), legs=[2], max_outliers=1)
    leg = tolerant.legs[0]
    assert leg.status == "consistent" and leg.outliers == [5]
    truth = json.loads((data / "truth.json").read_text())["legs"][1]
    values = np.array(truth["a"] + truth["b"] + [truth["l"]])
    assert np.all(leg.outer[:, 0] <= values) and np.all(values <= leg.outer[:, 1])
    same_legs(tolerant.to_dict(), cli_report(data, "--legs", "2", "--max-outliers", "1"))
    auto = certicalib.certify(*files(data), legs=[2], max_outliers="auto").legs[0]
    assert auto.outliers_tolerated == 1 and auto.outliers == [5]
    assert np.array_equal(auto.outer, leg.outer)
    with pytest.raises(ValueError, match="max_outliers"):
        certicalib.certify(*files(data), legs=[2], max_outliers="many")


def test_bad_input_raises_value_error_naming_file_line_and_field(data, tmp_path):
    bad = tmp_path / "measurements.csv"
    lines = (data / "measurements.csv").read_text().splitlines()
    cells = lines[3].split(",")
    cells[8] = "oops"  # the L2 column of the third configuration, on line 4
    lines[3] = ",".join(cells)
    bad.write_text("\n".join(lines) + "\n")
    robot, _, unc = files(data)
    with pytest.raises(ValueError) as e:
        certicalib.certify(robot, bad, unc)
    message = str(e.value)
    assert "measurements.csv" in message and "line 4" in message and "L2" in message, message
    with pytest.raises(ValueError, match="robot.toml"):
        broken = tmp_path / "robot.toml"
        broken.write_text("[[leg]]\na = [1, 2]\n")
        certicalib.certify(broken, data / "measurements.csv", unc)
    with pytest.raises(ValueError, match=r"robot \(in memory\): missing key"):
        certicalib.certify({"a": [[0, 0, 0]]}, data / "measurements.csv", unc)
    with pytest.raises(ValueError, match=r"uncertainty \(in memory\)"):
        certicalib.certify(robot, data / "measurements.csv", {"pos": -1.0, "len": 1e-3,
                                                              "axis": 1e-5, "angle_deg": 1e-3})
    with pytest.raises(ValueError, match="--legs"):
        certicalib.certify(*files(data), legs=[9])
    with pytest.raises(ValueError, match="--configs"):
        certicalib.simulate(tmp_path / "x", configs=3)


def test_least_squares_mirrors_the_cli(data):
    fits = certicalib.lsq(data / "robot.toml", data / "measurements.csv")
    assert [f.leg for f in fits] == [1, 2, 3, 4, 5, 6]
    truth = json.loads((data / "truth.json").read_text())["legs"][0]
    assert fits[0].x.shape == (7,) and abs(fits[0].x[0] - truth["a"][0]) < 0.1
    out = subprocess.run([str(repo_binary("gough")), "lsq", "--robot", str(data / "robot.toml"),
                          "--measurements", str(data / "measurements.csv")],
                         check=True, capture_output=True, text=True).stdout
    row = out.splitlines()[1].split()
    assert row[0] == "1" and abs(float(row[2]) - fits[0].x[0]) < 1e-4


def test_the_example_script_runs(tmp_path):
    script = REPO / "calib-py" / "examples" / "plot_boxes.py"
    shutil.copy(script, tmp_path)
    result = subprocess.run([sys.executable, str(tmp_path / "plot_boxes.py"), str(tmp_path / "b.png")],
                            capture_output=True, text=True, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "leg 6: consistent" in result.stdout


def test_simulate_at_given_poses_matches_the_cli(tmp_path):
    rows = [[x, y, z, 0.0, 0.0, 1.0, 5.0 + k]
            for k, (x, y, z) in enumerate([(-5, -5, 55), (5, -5, 55), (-5, 5, 55), (5, 5, 55),
                                           (-5, -5, 65), (5, -5, 65), (-5, 5, 65), (5, 5, 65)])]
    poses = tmp_path / "poses.csv"
    poses.write_text("px,py,pz,ax,ay,az,angle_deg\n"
                     + "".join(",".join(str(v) for v in r) + "\n" for r in rows))
    mine = tmp_path / "mine"
    truth = certicalib.simulate(mine, seed=3, poses=poses)
    assert truth["p"] == len(rows)
    cli = tmp_path / "cli"
    subprocess.run([str(repo_binary("gough")), "simulate", "--poses", str(poses), "--seed", "3",
                    "--out", str(cli)], check=True, capture_output=True)
    for name in ("measurements.csv", "robot.toml", "uncertainty.toml", "truth.json"):
        assert (mine / name).read_bytes() == (cli / name).read_bytes(), name
    poses.write_text(poses.read_text().replace("0.0,0.0,1.0,5.0", "0.0,0.0,3.0,5.0", 1))
    with pytest.raises(ValueError, match="poses.csv, line 2"):
        certicalib.simulate(tmp_path / "never", poses=poses)
    assert not (tmp_path / "never").exists()



def test_write_calibrated_carries_the_set_that_accuracy_works_over(tmp_path):
    certicalib.simulate(tmp_path, configs=21, seed=3)
    cal = tmp_path / "calibrated.toml"
    report = certicalib.certify(*files(tmp_path), write_calibrated=cal)
    assert all(leg.status == "consistent" for leg in report.legs)
    text = cal.read_text()
    tables = [line for line in text.splitlines() if line.strip() == "[leg.certified_set]"]
    assert len(tables) == 6, text[:400]
    ws = tmp_path / "workspace.toml"
    ws.write_text("x = [-1, 1]\ny = [-1, 1]\nz = [59, 61]\ntilt_deg = 2\n")
    acc = certicalib.accuracy(cal, ws, uncertainty=tmp_path / "uncertainty.toml",
                              pose_seconds=1, max_set_boxes=100)
    assert acc["over"] == "certified set"
    for leg in acc["leg_length"]:
        assert 0 < leg["lower"] <= leg["upper"]
    refined = certicalib.accuracy(cal, ws, uncertainty=tmp_path / "uncertainty.toml",
                                  pose_seconds=1, max_set_boxes=100, refine_set=True)
    assert refined["over"] == "certified set"
    for leg in refined["leg_length"]:
        assert 0 < leg["lower"] <= leg["upper"]
    # Held-out readings (a second simulation of the same robot: its truth is the same) lie in
    # their predictions over the set; the package gives the command line's JSON.
    held = tmp_path / "held"
    certicalib.simulate(held, configs=8, seed=3)
    mine = certicalib.predict(cal, tmp_path / "uncertainty.toml",
                              measurements=held / "measurements.csv")
    assert mine["refuting"] == [] and len(mine["rows"]) == 8
    out = tmp_path / "predict.json"
    subprocess.run([repo_binary("gough"), "predict", "--robot", str(cal), "--measurements",
                    str(held / "measurements.csv"), "--uncertainty",
                    str(tmp_path / "uncertainty.toml"), "--json", str(out)], check=True,
                   capture_output=True)
    assert json.loads(out.read_text()) == mine
    with pytest.raises(ValueError, match="poses or measurements"):
        certicalib.predict(cal, tmp_path / "uncertainty.toml")


def test_error_scale_matches_the_cli_and_brackets_within_two_per_cent(data):
    # Legs 1 and 4 are clean (leg 3's configuration 6 was moved 0.3 cm, far beyond any bound).
    found = certicalib.error_scale(*files(data), scale_bounds="all", legs=[1, 4])
    assert found["bounds"] == "all" and found["s_lo"] < found["s_hi"]
    assert found["s_hi"] / found["s_lo"] <= 1.02
    assert found["s_lo"] < found["estimate"] <= found["s_hi"] * (1 + 1e-9)
    cli = cli_report(data, "--fast", "--legs", "1,4", "--error-scale", "auto",
                     "--scale-bounds", "all")["error_scale"]
    assert (cli["s_lo"], cli["s_hi"]) == (found["s_lo"], found["s_hi"])
    with pytest.raises(ValueError, match="scale_bounds"):
        certicalib.error_scale(*files(data), scale_bounds="joint_deg")


def test_write_calibrated_for_a_task_gives_the_cli_file(tmp_path):
    certicalib.simulate(tmp_path, configs=21, seed=3)
    robot, meas, unc = files(tmp_path)
    poses = tmp_path / "poses.csv"
    poses.write_text("px,py,pz,ax,ay,az,angle_deg\n0,0,60,1,0,0,5\n3,-2,58,0,1,0,8\n")
    mine = tmp_path / "mine.toml"
    report = certicalib.certify(robot, meas, unc, legs=[1, 2], write_calibrated=mine, task=poses)
    assert all(leg.status == "consistent" for leg in report.legs)
    cli = tmp_path / "cli.toml"
    subprocess.run([repo_binary("gough"), "certify", "--robot", str(robot), "--measurements",
                    str(meas), "--uncertainty", str(unc), "--legs", "1,2",
                    "--write-calibrated", str(cli), "--task", str(poses)],
                   check=True, capture_output=True)
    body = lambda p: [l for l in p.read_text().splitlines() if not l.startswith("#")]
    assert body(mine) == body(cli)
    # A poses file with a column missing: named, nothing written.
    bad = tmp_path / "bad.csv"
    bad.write_text("px,py,pz,ax,ay,az\n0,0,60,1,0,0\n")
    never = tmp_path / "never.toml"
    with pytest.raises(ValueError, match="bad.csv"):
        certicalib.certify(robot, meas, unc, write_calibrated=never, task=bad)
    assert not never.exists()


def test_a_calibrated_robot_carries_its_rows_over_as_the_cli_does(tmp_path):
    # Two series of the same simulated hexapod (the truth does not depend on the seed): the
    # first calibrated, the second certified against the calibrated file.
    first, second = tmp_path / "first", tmp_path / "second"
    certicalib.simulate(first, configs=12, seed=21)
    certicalib.simulate(second, configs=12, seed=22)
    cal = tmp_path / "calibrated.toml"
    alone = certicalib.certify(*files(first), write_calibrated=cal)
    assert all(leg.carried_over == 0 for leg in alone.legs)
    both = certicalib.certify(cal, second / "measurements.csv", second / "uncertainty.toml",
                              write_calibrated=tmp_path / "again.toml")
    assert [leg.carried_over for leg in both.legs] == [12] * 6
    assert all(leg.status == "consistent" for leg in both.legs)
    assert both.to_dict()["legs"][0]["carried_over"]["first"] == 13
    # The command line certifies the same rows from the same boxes.
    out = tmp_path / "cli.json"
    subprocess.run([str(repo_binary("gough")), "certify", "--robot", str(cal), "--measurements",
                    str(second / "measurements.csv"), "--uncertainty",
                    str(second / "uncertainty.toml"), "--json", str(out)], check=True,
                   capture_output=True)
    cli = json.loads(out.read_text())
    same_legs(both.to_dict(), cli)
    assert [leg["carried_over"] for leg in cli["legs"]] == \
        [leg["carried_over"] for leg in both.to_dict()["legs"]]
    # The file written stores both series: a second round carries 24 rows.
    again = certicalib.certify(tmp_path / "again.toml", *files(first)[1:])
    assert [leg.carried_over for leg in again.legs] == [24] * 6
