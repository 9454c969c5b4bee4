"""certicalib.design: the poses it writes lie in the workspace, the plan matches
``gough design --json`` for the same arguments, and bad files are ValueErrors naming them."""

import json
import os
import subprocess

import numpy as np
import pytest

import certicalib
from cli_binaries import repo_binary

WORKSPACE = "x = [-4, 4]\ny = [-3, 5]\nz = [56, 63]\ntilt_deg = 12\nstroke = [0, 15]\n"


def test_design_writes_poses_in_the_workspace_and_beats_random(tmp_path):
    ws = tmp_path / "workspace.toml"
    ws.write_text(WORKSPACE)
    out = tmp_path / "poses.csv"
    plan = certicalib.design(out, workspace=ws, configs=9, candidates=300, seed=4)
    assert plan.poses.shape == (9, 7)
    rows = np.loadtxt(out, delimiter=",", skiprows=1)
    np.testing.assert_array_equal(rows, plan.poses)
    assert np.all((-4 <= rows[:, 0]) & (rows[:, 0] <= 4))
    assert np.all((-3 <= rows[:, 1]) & (rows[:, 1] <= 5))
    assert np.all((56 <= rows[:, 2]) & (rows[:, 2] <= 63))
    assert np.all(np.abs(rows[:, 6]) <= 12)
    assert np.allclose(np.linalg.norm(rows[:, 3:6], axis=1), 1.0)
    assert plan.geometric_mean["designed"] < plan.geometric_mean["random"]
    assert plan.widths["designed"].shape == (6, 7)
    # The designed poses simulate end to end.
    truth = certicalib.simulate(tmp_path / "data", poses=out, seed=2)
    assert truth["p"] == 9


def test_design_matches_the_command_line(tmp_path):
    out = tmp_path / "py.csv"
    plan = certicalib.design(out, configs=7, candidates=150, criterion="d-optimal", seed=3)
    cli_out, cli_json = tmp_path / "cli.csv", tmp_path / "cli.json"
    subprocess.run([repo_binary("gough"), "design", "--configs", "7",
                    "--candidates", "150", "--criterion", "d-optimal", "--seed", "3",
                    "--out", str(cli_out), "--json", str(cli_json)],
                   check=True, capture_output=True)
    assert out.read_text() == cli_out.read_text()
    cli = json.loads(cli_json.read_text())
    mine = plan.to_dict()
    for key in ("poses", "predicted", "first_order", "matching_prefix", "criterion"):
        assert mine[key] == cli[key], key


def test_bad_inputs_are_value_errors_naming_the_file(tmp_path):
    ws = tmp_path / "workspace.toml"
    ws.write_text("x = [-4, 4]\ny = [3, -3]\nz = [56, 63]\ntilt_deg = 12\n")
    out = tmp_path / "poses.csv"
    with pytest.raises(ValueError, match=r"workspace.toml, line 2, field `y`"):
        certicalib.design(out, workspace=ws)
    with pytest.raises(ValueError, match="criterion"):
        certicalib.design(out, criterion="a-optimal")
    assert not os.path.exists(out)


def test_accuracy_matches_the_command_line(tmp_path):
    certicalib.simulate(tmp_path, seed=5)
    ws = tmp_path / "workspace.toml"
    ws.write_text(WORKSPACE)
    robot = tmp_path / "robot.toml"
    mine = certicalib.accuracy(robot, ws, uncertainty=tmp_path / "uncertainty.toml")
    out = tmp_path / "accuracy.json"
    subprocess.run([repo_binary("gough"), "accuracy", "--robot", str(robot), "--workspace",
                    str(ws), "--uncertainty", str(tmp_path / "uncertainty.toml"),
                    "--json", str(out)], check=True, capture_output=True)
    cli = json.loads(out.read_text())
    assert mine["leg_length"] == cli["leg_length"]
    for key in ("position", "orientation"):
        # The pose-error bounds stop on a time budget, so where they stop depends on the
        # machine's load: the two runs must agree as brackets (each proved upper bound at least
        # the other run's attained lower bound), not to the bit.
        for a, b in ((mine, cli), (cli, mine)):
            assert b[key]["upper"] is None or b[key]["upper"] >= a[key]["lower"]
        upper, lower = mine[key]["upper"], mine[key]["lower"]
        assert lower > 0 and (upper is None or upper >= lower)
        assert upper is not None or mine[key]["upper_unproved_at"] is not None
        if upper is None:
            why = mine[key]["upper_unproved"]
            assert isinstance(why["finest"], bool) and 0 <= why["settled_share"] < 1
    assert mine["actuator"] == cli["actuator"] == 0.0005
    for leg in mine["leg_length"]:
        assert 0 < leg["lower"] <= leg["upper"] <= 1.05 * leg["lower"]
    bad = tmp_path / "bad.toml"
    bad.write_text("x = [-4, 4]\ny = [-3, 5]\nz = [56, 63]\ntilt_deg = 190\n")
    with pytest.raises(ValueError, match=r"bad.toml, line 4, field `tilt_deg`"):
        certicalib.accuracy(robot, bad)
    with pytest.raises(ValueError, match="pose_seconds"):
        certicalib.accuracy(robot, ws, pose_seconds=0)
