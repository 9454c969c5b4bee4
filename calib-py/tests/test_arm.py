"""The Python package's serial arm against the arm CLI: the same JSON report, the truth inside the
certified box, outliers found with max_outliers="auto", ValueError naming the file on bad input."""
import hashlib
import json
import re
import subprocess
from pathlib import Path

import numpy as np
import pytest

import certicalib
from cli_binaries import REPO, repo_binary


# A 3-joint arm with small priors (seconds to certify; the built-in 6-axis arm takes longer),
# shared with the arm CLI tests.
ROBOT = (REPO / "calib-arm" / "tests" / "data" / "small_arm.toml").read_text()


def simulated(d: Path, **kwargs) -> dict:
    design = d / "design.toml"
    design.write_text(ROBOT)
    return certicalib.simulate_arm(d, configs=12, seed=5, robot=design, **kwargs)


def files(d: Path):
    return d / "robot.toml", d / "measurements.csv", d / "uncertainty.toml"


def test_the_report_is_the_cli_report_and_keeps_the_truth(tmp_path):
    truth = simulated(tmp_path)
    report = certicalib.certify_arm(*files(tmp_path), lsq=True)
    assert report.status == "consistent"
    free = ~report.fixed
    values = np.array([truth[name] for name in report.names])
    assert np.all(report.outer[free, 0] <= values[free])
    assert np.all(values[free] <= report.outer[free, 1])
    assert np.all(report.outer[:, 0] <= report.inner[:, 0])
    assert np.all(report.inner[:, 1] <= report.outer[:, 1])
    assert report.lsq is not None and report.lsq.shape == (len(report.names),)
    assert np.all(report.ratio[free] >= 1.0)
    out = tmp_path / "cli.json"
    robot, meas, unc = files(tmp_path)
    subprocess.run([str(repo_binary("arm")), "certify", "--robot", str(robot), "--measurements",
                    str(meas), "--uncertainty", str(unc), "--lsq", "--json", str(out)],
                   check=True, capture_output=True)
    cli = json.loads(out.read_text())
    mine = report.to_dict()
    for key in ("status", "parameters", "conflict", "outliers", "verdict", "identifiability"):
        assert mine[key] == cli[key], key


def test_auto_outliers_name_the_shifted_configuration(tmp_path):
    simulated(tmp_path, outliers=[(4, 0.5)])
    strict = certicalib.certify_arm(*files(tmp_path))
    assert strict.status == "empty" and strict.outer is None and 4 in strict.conflict
    auto = certicalib.certify_arm(*files(tmp_path), max_outliers="auto")
    assert auto.status == "consistent"
    assert auto.outliers_tolerated == 1 and auto.outliers == [4]
    fixed = certicalib.certify_arm(*files(tmp_path), max_outliers=1)
    assert np.array_equal(fixed.outer, auto.outer)
    with pytest.raises(ValueError, match="max_outliers"):
        certicalib.certify_arm(*files(tmp_path), max_outliers="several")


def test_bad_input_raises_value_error_naming_the_file(tmp_path):
    simulated(tmp_path)
    robot = tmp_path / "robot.toml"
    robot.write_text(robot.read_text().replace("d = 120.0", "d = oops", 1))
    with pytest.raises(ValueError, match="robot.toml"):
        certicalib.certify_arm(*files(tmp_path))
    with pytest.raises(ValueError, match="configuration must be"):
        certicalib.simulate_arm(tmp_path / "x", configs=5, outliers=[(9, 0.5)])


def test_the_module_examples_run():
    import doctest

    result = doctest.testmod(certicalib)
    assert result.attempted >= 10 and result.failed == 0


def test_write_calibrated_gives_the_cli_file_and_fits_the_data(tmp_path):
    simulated(tmp_path)
    mine = tmp_path / "mine.toml"
    report = certicalib.certify_arm(*files(tmp_path), write_calibrated=mine)
    assert report.status == "consistent"
    cli = tmp_path / "cli.toml"
    robot, meas, unc = files(tmp_path)
    subprocess.run([repo_binary("arm"), "certify", "--robot", str(robot), "--measurements",
                    str(meas), "--uncertainty", str(unc), "--write-calibrated", str(cli)],
                   check=True, capture_output=True)
    # The same parameters and set as the command line (its comment lines differ).
    body = lambda p: [l for l in p.read_text().splitlines() if not l.startswith("#")]
    assert body(mine) == body(cli)
    assert "[certified_set]" in mine.read_text()
    # Every measured point lies within its prediction over the set (the arm predict check).
    out = tmp_path / "check.json"
    subprocess.run([repo_binary("arm"), "predict", "--robot", str(mine), "--measurements",
                    str(meas), "--uncertainty", str(unc), "--json", str(out)], check=True,
                   capture_output=True)
    check = json.loads(out.read_text())
    assert check["over"] == "certified set" and check["refuting"] == []
    # The package's predict_arm gives the command line's JSON.
    assert certicalib.predict_arm(mine, unc, meas) == check


def test_accuracy_arm_is_the_cli_report_over_the_certified_set(tmp_path):
    simulated(tmp_path)
    cal = tmp_path / "cal.toml"
    robot, meas, unc = files(tmp_path)
    assert certicalib.certify_arm(robot, meas, unc, write_calibrated=cal).status == "consistent"
    cell = tmp_path / "cell.toml"
    cell.write_text("q1 = [10, 20]\nq2 = [-30, -20]\nq3 = [40, 50]\n")
    page = tmp_path / "accuracy.html"
    mine = certicalib.accuracy_arm(cal, joints=cell, before=robot, uncertainty=unc,
                                   max_set_boxes=20, max_boxes=500, report=page)
    out = tmp_path / "accuracy.json"
    subprocess.run([repo_binary("arm"), "accuracy", "--robot", str(cal), "--joints", str(cell),
                    "--before", str(robot), "--uncertainty", str(unc), "--max-set-boxes", "20",
                    "--max-boxes", "500", "--json", str(out)], check=True, capture_output=True)
    cli = json.loads(out.read_text())
    # The same report but for the wall-clock seconds.
    for r in (mine, cli):
        for key in ("position", "before"):
            r[key].pop("seconds")
    assert mine == cli
    after = mine["position"]
    assert after["over"] == "certified set"
    assert 0 < after["lower"] <= after["upper"]
    assert mine["before"]["lower"] > 0 and mine["improvement"] is not None
    # The certificate states the brackets it returned and identifies the joint space file.
    html = page.read_text()
    assert "What calibration bought" in html
    row = re.search(r'<td class="num">after calibration</td><td class="num">([^<]+)</td>'
                    r'<td class="num">([^<]+)</td>', html)
    upper, lower = float(row.group(1)), float(row.group(2))
    # Printed to 1e-5, the upper bound rounded up and the lower one down: still bounds.
    assert after["upper"] <= upper <= after["upper"] + 1e-5
    assert after["lower"] - 1e-5 <= lower <= after["lower"]
    assert hashlib.sha256(cell.read_bytes()).hexdigest() in html
    # At a task's configurations, each as given: the command line's report.
    task = tmp_path / "task.csv"
    task.write_text("q1,q2,q3\n12,-25,41\n18,-22,49\n-60,80,10\n")
    mine = certicalib.accuracy_arm(cal, task=task, before=robot, uncertainty=unc)
    subprocess.run([repo_binary("arm"), "accuracy", "--robot", str(cal), "--task", str(task),
                    "--before", str(robot), "--uncertainty", str(unc), "--json", str(out)],
                   check=True, capture_output=True)
    cli = json.loads(out.read_text())
    # The configurations are shared among threads whose programs warm-start from their own
    # earlier ones: the bounds agree to rounding, the rest exactly.
    for key in ("position", "before"):
        for field in ("upper", "lower", "ratio"):
            a, b = mine[key].pop(field), cli[key].pop(field)
            assert abs(a - b) <= 1e-9 * abs(b), (key, field, a, b)
        for r in (mine, cli):
            r[key].pop("seconds")
    a, b = mine.pop("improvement"), cli.pop("improvement")
    assert abs(a - b) <= 1e-9 * abs(b)
    assert mine == cli
    worst = mine["position"]["worst"]["joints_deg"]
    assert mine["position"]["boxes"] == 3 and any(
        all(abs(a - b) < 1e-9 for a, b in zip(worst, q))
        for q in ([12, -25, 41], [18, -22, 49], [-60, 80, 10]))


def test_write_calibrated_for_a_task_gives_the_cli_file(tmp_path):
    simulated(tmp_path)
    robot, meas, unc = files(tmp_path)
    cell = tmp_path / "cell.toml"
    cell.write_text("q1 = [10, 20]\nq2 = [-30, -20]\nq3 = [40, 50]\n")
    mine = tmp_path / "mine.toml"
    report = certicalib.certify_arm(robot, meas, unc, write_calibrated=mine, task=cell)
    assert report.status == "consistent"
    cli = tmp_path / "cli.toml"
    subprocess.run([repo_binary("arm"), "certify", "--robot", str(robot), "--measurements",
                    str(meas), "--uncertainty", str(unc), "--write-calibrated", str(cli),
                    "--task", str(cell)], check=True, capture_output=True)
    body = lambda p: [l for l in p.read_text().splitlines() if not l.startswith("#")]
    assert body(mine) == body(cli)
    assert "over the task" in mine.read_text()
    # A task file with the wrong columns: named, nothing written.
    bad = tmp_path / "bad.csv"
    bad.write_text("q1,q2\n0,1\n")
    never = tmp_path / "never.toml"
    with pytest.raises(ValueError, match="bad.csv"):
        certicalib.certify_arm(robot, meas, unc, write_calibrated=never, task=bad)
    assert not never.exists()
