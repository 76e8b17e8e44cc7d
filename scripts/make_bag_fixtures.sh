#!/usr/bin/env bash
# Writes the bag fixtures of data/bags/ (docs/bags.md, "Fixtures") with writers independent of
# splinecal: Debian's python3-rosbag (ROS 1 bags), @mcap/core and @foxglove/rosmsg2-serialization
# (MCAP, and the CDR of the rosbag2 sqlite3 recording, written into rosbag2's schema by Python's
# sqlite3). Needs: apt-get install python3-rosbag python3-sensor-msgs python3-roslz4; node + npm.
#   scripts/make_bag_fixtures.sh
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp "$repo/scripts/fixtures/package.json" "$repo/scripts/fixtures/make_mcap_fixtures.mjs" \
  "$repo/scripts/fixtures/ros2_definitions.mjs" "$work/"
(cd "$work" && npm install --no-audit --no-fund --silent >/dev/null)
rm -rf "$repo/data/bags"
node "$work/make_mcap_fixtures.mjs" "$repo" "$work"
/usr/bin/python3 "$repo/scripts/fixtures/make_ros_fixtures.py" "$repo" "$work"
# The recording the --bag tests run every command on (needs a built splinecal, for the simulated
# calibration half; make_calibration_bag.py says what is in it).
splinecal=${SPLINECAL:-$repo/build/splinecal}
"$splinecal" simulate --trajectory calibration --duration 3 --camera-rate 5 \
  --camchain "$repo/data/calibration/camchain_truth.yaml" \
  --target "$repo/data/calibration/aprilgrid.yaml" --seed 2 --quiet --out "$work/sim" >/dev/null
/usr/bin/python3 "$repo/scripts/fixtures/make_calibration_bag.py" "$repo" "$work/sim"
du -sh "$repo/data/bags"
