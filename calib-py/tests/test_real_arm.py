"""The real UR10 (docs/data/ur10_ipa) through the Python package: UR's YAML in, the tracker
registered from its own file, the smallest consistent error bound bracketed with proofs, the
kinematics out — the same as the arm commands, and file mistakes raised as ValueError."""

import subprocess

import pytest

import certicalib
from cli_binaries import REPO, repo_binary

DATA = REPO / "docs" / "data" / "ur10_ipa"
SERIES = DATA / "series_b_joint_configurations.csv"
JOINTS = ["shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint",
          "wrist_2_joint", "wrist_3_joint"]
POINT = ["measurement_x", "measurement_y", "measurement_z"]
TRACKER = dict(joint_columns=JOINTS, point_columns=POINT, joint_unit="rad")


def test_import_register_error_scale_export(tmp_path):
    nominal = tmp_path / "nominal.toml"
    text = certicalib.import_arm(DATA / "ur10_default_kinematics.yaml", nominal)
    assert "d = 127.3" in text and nominal.exists()
    robot = tmp_path / "robot.toml"
    reg = certicalib.register_arm(nominal, SERIES, robot, rows="1-40", **TRACKER)
    assert reg["converged"] and reg["rms_mm"] < 1.5
    assert abs(reg["tool"][2] - 93.0) < 2.0
    # The command line registers the same.
    cli = tmp_path / "cli.toml"
    subprocess.run([repo_binary("arm"), "register", "--robot", str(nominal), "--measurements",
                    str(SERIES), "--joint-columns", ",".join(JOINTS), "--point-columns",
                    ",".join(POINT), "--joint-unit", "rad", "--rows", "1-40", "--out", str(cli)],
                   check=True, capture_output=True)
    assert robot.read_text().split("\n", 1)[1] == cli.read_text().split("\n", 1)[1]
    u = tmp_path / "u.toml"
    u.write_text("joint_deg = 0.001\npos = 0.05\n")
    scale = certicalib.error_scale_arm(robot, SERIES, u, scale_bounds="pos", rows="1-40",
                                       **TRACKER)
    # Both ends are proofs of their kind, and the tracker's 0.05 mm is far too small.
    verdict = {t["scale"]: t["verdict"] for t in scale["trials"]}
    assert verdict[scale["s_lo"]] == "empty" and verdict[scale["s_hi"]] == "consistent"
    assert 1.0 < scale["s_lo"] < scale["s_hi"] and scale["bounds"] == "pos"
    yaml = tmp_path / "out.yaml"
    certicalib.export_arm(robot, ur_yaml=yaml)
    assert yaml.read_text().count("roll:") == 6 and "hash: certicalib_" in yaml.read_text()


def test_mistakes_raise_value_errors_naming_the_file(tmp_path):
    nominal = tmp_path / "nominal.toml"
    certicalib.import_arm(DATA / "ur10_default_kinematics.yaml", nominal)
    with pytest.raises(ValueError, match=r"line 2.*measurement_x.*--length-unit mm"):
        certicalib.register_arm(nominal, SERIES, tmp_path / "x.toml", rows="1-40",
                                length_unit="m", **TRACKER)
    with pytest.raises(ValueError, match="joint_unit"):
        certicalib.register_arm(nominal, SERIES, tmp_path / "x.toml", joint_columns=JOINTS,
                                point_columns=POINT, joint_unit="grad")
    with pytest.raises(ValueError, match="kind"):
        certicalib.import_arm(DATA / "ur10_default_kinematics.yaml", tmp_path / "y.toml",
                              kind="dh")
    assert not (tmp_path / "x.toml").exists() and not (tmp_path / "y.toml").exists()
    # A least-squares fit that `arm lsq --out` marks as not proved consistent is no calibration.
    fit = tmp_path / "lsq.toml"
    fit.write_text(nominal.read_text() + "\n[least_squares]\nproved_consistent = false\n")
    with pytest.raises(ValueError, match=r"lsq.toml, line \d+.*least_squares.proved_consistent"):
        certicalib.export_arm(fit, ur_yaml=tmp_path / "fit.yaml")
    assert not (tmp_path / "fit.yaml").exists()
    certicalib.export_arm(nominal, ur_yaml=tmp_path / "nominal.yaml")


def test_register_finds_the_tool_frame_from_the_tmac_orientations(tmp_path):
    nominal = tmp_path / "nominal.toml"
    certicalib.import_arm(DATA / "ur10_default_kinematics.yaml", nominal)
    robot = tmp_path / "robot6.toml"
    orientation = ["measurement_rx", "measurement_ry", "measurement_rz"]
    reg = certicalib.register_arm(nominal, SERIES, robot, rows="1-40",
                                  orientation_columns=orientation, tool_rotation_radius=0.3,
                                  **TRACKER)
    rotation = reg["tool_rotation"]
    assert abs(rotation["rpy_deg"][2] + 90.0) < 1.0 and 0.0 < rotation["rms_deg"] < 0.2
    # The command line writes the same robot file.
    cli = tmp_path / "cli6.toml"
    subprocess.run([repo_binary("arm"), "register", "--robot", str(nominal), "--measurements",
                    str(SERIES), "--joint-columns", ",".join(JOINTS), "--point-columns",
                    ",".join(POINT), "--joint-unit", "rad", "--rows", "1-40",
                    "--orientation-columns", ",".join(orientation),
                    "--tool-rotation-radius", "0.3", "--out", str(cli)],
                   check=True, capture_output=True)
    assert robot.read_text().split("\n", 1)[1] == cli.read_text().split("\n", 1)[1]
    assert "rotation_radius = [0.3, 0.3, 0.3]" in robot.read_text()
    # How much error positions and orientations need together: both ends proofs of their kind.
    u = tmp_path / "u6.toml"
    u.write_text("joint_deg = 0.001\npos = 0.05\norient_deg = 0.01\n")
    scale = certicalib.error_scale_arm(robot, SERIES, u, rows="1-20",
                                       orientation_columns=orientation, **TRACKER)
    verdict = {t["scale"]: t["verdict"] for t in scale["trials"]}
    assert verdict[scale["s_lo"]] == "empty" and verdict[scale["s_hi"]] == "consistent"
    assert 1.0 < scale["s_lo"] < scale["s_hi"] and scale["bounds"] == "all"
    with pytest.raises(ValueError, match="--orientation-columns"):
        certicalib.error_scale_arm(robot, SERIES, u, rows="1-20", scale_bounds="orient_deg",
                                   **TRACKER)
    assert certicalib.register_arm(nominal, SERIES, tmp_path / "p.toml", rows="1-40",
                                   **TRACKER)["tool_rotation"] is None
    with pytest.raises(ValueError, match="orientation_convention"):
        certicalib.register_arm(nominal, SERIES, tmp_path / "x.toml", rows="1-40",
                                orientation_columns=orientation,
                                orientation_convention="quaternion", **TRACKER)
    assert not (tmp_path / "x.toml").exists()


def test_certify_six_dof_writes_a_calibrated_tool_frame(tmp_path):
    nominal = tmp_path / "nominal.toml"
    certicalib.import_arm(DATA / "ur10_default_kinematics.yaml", nominal)
    robot = tmp_path / "robot6.toml"
    orientation = ["measurement_rx", "measurement_ry", "measurement_rz"]
    certicalib.register_arm(nominal, SERIES, robot, rows="1-30",
                            orientation_columns=orientation, **TRACKER)
    u = tmp_path / "u6.toml"
    u.write_text("joint_deg = 0.001\npos = 0.6\norient_deg = 0.2\n")
    calibrated = tmp_path / "calibrated6.toml"
    report = certicalib.certify_arm(robot, SERIES, u, rows="1-30", write_calibrated=calibrated,
                                    orientation_columns=orientation, **TRACKER)
    assert report.status == "consistent"
    # The tool frame's three angles are parameters of the 6-DoF run, and the written file holds
    # its calibrated rotation; the same run from the command line agrees on the verdict.
    assert {"tool_rx", "tool_ry", "tool_rz"} <= set(report.names)
    assert "rpy_deg" in calibrated.read_text()
    cli = subprocess.run([repo_binary("arm"), "certify", "--robot", str(robot),
                          "--measurements", str(SERIES), "--joint-columns", ",".join(JOINTS),
                          "--point-columns", ",".join(POINT), "--joint-unit", "rad",
                          "--rows", "1-30", "--orientation-columns", ",".join(orientation),
                          "--uncertainty", str(u)], capture_output=True, text=True)
    assert cli.returncode == 0 and "verdict: consistent" in cli.stdout
    # Held-out orientations against the calibrated tool frame, as `arm predict` reports them.
    u_pos = tmp_path / "u_pos.toml"
    u_pos.write_text("joint_deg = 0.001\npos = 0.6\n")
    check = certicalib.predict_arm(calibrated, u_pos, SERIES, rows="61-80",
                                   orientation_columns=orientation, **TRACKER)
    residuals = check["orientation_residuals"]
    assert len(residuals["per_row_deg"]) == 20 and 0.0 < residuals["rms_deg"] < 0.2
    assert "orientation_residuals" not in certicalib.predict_arm(calibrated, u_pos, SERIES,
                                                                 rows="61-80", **TRACKER)
    # Orientations without their bound, or without the tool frame's rotation: a ValueError
    # naming the file, and nothing written.
    with pytest.raises(ValueError, match="u_pos.toml.*orient_deg"):
        certicalib.certify_arm(robot, SERIES, tmp_path / "u_pos.toml", rows="1-30",
                               write_calibrated=tmp_path / "x.toml",
                               orientation_columns=orientation, **TRACKER)
    with pytest.raises(ValueError, match="nominal.toml.*rpy_deg"):
        certicalib.certify_arm(nominal, SERIES, u, rows="1-30",
                               write_calibrated=tmp_path / "x.toml",
                               orientation_columns=orientation, **TRACKER)
    assert not (tmp_path / "x.toml").exists()


def test_a_calibration_carries_over_to_new_rows_in_their_own_frame(tmp_path):
    nominal = tmp_path / "nominal.toml"
    certicalib.import_arm(DATA / "ur10_default_kinematics.yaml", nominal)
    robot = tmp_path / "robot.toml"
    certicalib.register_arm(nominal, SERIES, robot, rows="1-40", **TRACKER)
    u = tmp_path / "u.toml"
    u.write_text("joint_deg = 0.001\npos = 0.45\n")
    calibrated = tmp_path / "calibrated.toml"
    first = certicalib.certify_arm(robot, SERIES, u, rows="1-40", write_calibrated=calibrated,
                                   **TRACKER)
    assert first.status == "consistent" and first.carried_over is None
    # The next cell: registered from the calibrated file, which hands its set on.
    here = tmp_path / "here.toml"
    certicalib.register_arm(calibrated, SERIES, here, rows="41-80", **TRACKER)
    assert "[carried_set]" in here.read_text() and "[certified_set]" not in here.read_text()
    both = certicalib.certify_arm(here, SERIES, u, rows="41-80", **TRACKER)
    assert both.carried_over == {"file": "here.toml", "configurations": 40}
    assert both.status == "consistent"
    alone = certicalib.certify_arm(robot, SERIES, u, rows="41-80", **TRACKER)
    # The joints' parameters (before the base's nine): narrower together with the earlier rows.
    joints = len(both.names) - 9
    width = lambda box: float((box[:joints, 1] - box[:joints, 0]).sum())  # noqa: E731
    assert width(both.outer) < width(alone.outer)
