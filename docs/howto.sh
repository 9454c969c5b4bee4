#!/usr/bin/env bash
# The how-to guides' commands (docs/src/howto/), as written there; CI runs them. What a page takes
# as already at hand (a robot file, a data set with a bad reading, a URDF) is made first, marked
# "at hand". Exit 2 is a verdict (proved inconsistent), not a failure, where a page allows it.
# Usage: docs/howto.sh [GOUGH_BINARY] [ARM_BINARY] [WORK_DIR]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
gough="${1:-gough}"
arm="${2:-arm}"
work="${3:-$(mktemp -d)}"
mkdir -p "$work"
cd "$work"
ln -sfn "$here" docs  # the pages name files as docs/data/…, from the repository's top
verdict() { "$@" || [ $? -eq 2 ]; }

# design.md. At hand: sample21's robot, bounds, workspace and measurements.
cp docs/data/sample21/robot.toml docs/data/sample21/uncertainty.toml \
   docs/data/sample21/workspace.toml docs/data/sample21/measurements.csv .
"$gough" design --configs 21 --out poses.csv
"$gough" design --robot robot.toml --uncertainty uncertainty.toml --workspace workspace.toml \
             --configs 21 --out poses.csv
"$gough" design --robot robot.toml --extend measurements.csv --configs 5 --out next.csv

# outliers.md. At hand: a hexapod and an arm data set, each with one bad reading.
"$gough" simulate --configs 21 --seed 7 --outlier 5:2:0.1 --out bad
"$arm" simulate --configs 50 --seed 7 --outlier 12:0.5 --out armbad
verdict "$gough" certify --robot bad/robot.toml --measurements bad/measurements.csv \
              --uncertainty bad/uncertainty.toml --max-outliers 1
verdict "$arm" certify --robot armbad/robot.toml --measurements armbad/measurements.csv \
            --uncertainty armbad/uncertainty.toml --max-outliers auto

# remeasuring.md, on sample21 cut in two series.
d=docs/data/sample21
head -12 $d/measurements.csv > january.csv
(head -1 $d/measurements.csv; tail -n +13 $d/measurements.csv) > february.csv
"$gough" certify --robot $d/robot.toml --measurements january.csv \
              --uncertainty $d/uncertainty.toml --write-calibrated calibrated.toml
"$gough" certify --robot calibrated.toml --measurements february.csv \
              --uncertainty $d/uncertainty.toml --write-calibrated calibrated-feb.toml
rm calibrated.toml calibrated-feb.toml  # the arm's pages below write a calibrated.toml of their own

# vendor-files.md. At hand: a URDF (here the nominal UR10's, as `arm export` writes it).
"$arm" import --ur-yaml docs/data/ur10_ipa/ur10_default_kinematics.yaml --out nominal.toml
"$arm" export --robot nominal.toml --urdf robot.urdf
"$arm" import --urdf robot.urdf --base-link base_link --tip-link link6 --out nominal.toml

# registration.md and tracker-files.md, on the real UR10's series.
series=docs/data/ur10_ipa/series_b_joint_configurations.csv
columns="--joint-columns shoulder_pan_joint,shoulder_lift_joint,elbow_joint,wrist_1_joint,wrist_2_joint,wrist_3_joint --joint-unit rad --point-columns measurement_x,measurement_y,measurement_z"
# shellcheck disable=SC2086 # $columns is several flags, as the pages write it
"$arm" register --robot nominal.toml --measurements $series $columns --rows 1-60 --out robot.toml
# At hand: the bounds (the tutorial's held-out ones).
printf 'joint_deg = 0.001\npos = 0.45\n' > uncertainty.toml
verdict "$arm" certify --robot robot.toml --measurements $series \
            --joint-columns shoulder_pan_joint,shoulder_lift_joint,elbow_joint,wrist_1_joint,wrist_2_joint,wrist_3_joint \
            --joint-unit rad --point-columns measurement_x,measurement_y,measurement_z \
            --rows 1-60 --uncertainty uncertainty.toml
# The tracker moved. At hand: a calibrated robot, and the new cell's file (here the same series
# stands in for it).
# shellcheck disable=SC2086
"$arm" certify --robot robot.toml --measurements $series $columns --rows 1-60 \
               --uncertainty uncertainty.toml --write-calibrated calibrated.toml
cp "$series" new.csv
printf 'joint_deg = 0.001\npos = 0.05\n' > uncertainty.toml
printf 'joint_deg = 0.001\npos = 0.45\n' > held_out_bounds.toml
# shellcheck disable=SC2086
"$arm" register --robot calibrated.toml --measurements new.csv $columns --rows 1-60 --out here.toml
# shellcheck disable=SC2086
"$arm" certify --robot here.toml --measurements new.csv $columns --rows 1-60 \
            --uncertainty uncertainty.toml --error-scale auto --scale-bounds pos --scale-margin 1.1 \
            --write-calibrated calibrated-here.toml
# shellcheck disable=SC2086
verdict "$arm" predict --robot calibrated-here.toml --measurements new.csv $columns --rows 61- \
            --uncertainty held_out_bounds.toml

# vendor-files.md, out: the calibrated kinematics for the controller.
"$arm" export --robot calibrated.toml --ur-yaml calibrated_kinematics.yaml --urdf calibrated.urdf
echo "how-to commands done in $work"
