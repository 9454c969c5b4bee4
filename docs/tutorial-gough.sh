#!/usr/bin/env bash
# The hexapod tutorial (docs/src/tutorials/hexapod.md), every command as written there; CI runs it.
# Usage: docs/tutorial-gough.sh [GOUGH_BINARY] [WORK_DIR]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
gough="${1:-gough}"
work="${2:-$(mktemp -d)}"
mkdir -p "$work"
cd "$work"
data="$here/data/sample21"

# 1. Certify every leg: outer and inner bounds, the calibrated robot file, the certificate.
"$gough" certify --robot "$data/robot.toml" --measurements "$data/measurements.csv" \
                 --uncertainty "$data/uncertainty.toml" \
                 --write-calibrated calibrated.toml --json report.json --report certificate.html
# 2. The classical answer, for comparison: least squares per leg.
"$gough" lsq --robot "$data/robot.toml" --measurements "$data/measurements.csv"
# 3. How much error do these data need?
"$gough" certify --robot "$data/robot.toml" --measurements "$data/measurements.csv" \
                 --uncertainty "$data/uncertainty.toml" --error-scale auto --scale-margin 1.1 \
                 --fast
# 4. A bad reading: leg 2 of configuration 5 off by 0.1 cm, proved, named, then tolerated.
"$gough" simulate --configs 21 --seed 7 --outlier 5:2:0.1 --out bad
status=0
"$gough" certify --robot bad/robot.toml --measurements bad/measurements.csv \
                 --uncertainty bad/uncertainty.toml --legs 2 --fast || status=$?
# 2 = a leg proved empty: the point of this step.
[ "$status" -eq 2 ]
"$gough" certify --robot bad/robot.toml --measurements bad/measurements.csv \
                 --uncertainty bad/uncertainty.toml --legs 2 --max-outliers auto
# 5. The held-out check: calibrate on the first 15 configurations, predict the last 6.
head -n 16 "$data/measurements.csv" > first15.csv
{ head -n 1 "$data/measurements.csv"; tail -n 6 "$data/measurements.csv"; } > last6.csv
"$gough" certify --robot "$data/robot.toml" --measurements first15.csv \
                 --uncertainty "$data/uncertainty.toml" --write-calibrated calibrated15.toml
"$gough" predict --robot calibrated15.toml --measurements last6.csv \
                 --uncertainty "$data/uncertainty.toml" --json held_out.json
# 6. Accuracy over a workspace: how far the commanded leg lengths (and the platform) can be off.
printf 'x = [-1.0, 1.0]\ny = [-1.0, 1.0]\nz = [59.0, 61.0]\ntilt_deg = 2.0\n' > workspace.toml
"$gough" accuracy --robot calibrated.toml --workspace workspace.toml --before "$data/robot.toml" \
                  --uncertainty "$data/uncertainty.toml" --max-set-boxes 200 --pose-seconds 2 \
                  --tolerance 0.1 --json accuracy.json
# 7. The certificate is one self-contained page.
test -s certificate.html
# 8. Which configurations to measure next, to determine what these data leave open.
"$gough" design --robot "$data/robot.toml" --uncertainty "$data/uncertainty.toml" \
                --extend "$data/measurements.csv" --configs 7 --out next.csv
echo "tutorial done in $work"
