#!/usr/bin/env bash
# The splinecal pipeline on bundled and simulated data: installs what is missing, builds
# (Release) and runs each command, printing a short summary of each. Results go to demo-out/.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
command -v python3 >/dev/null || { sudo=(); [[ $(id -u) -ne 0 ]] && sudo=(sudo);
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq python3-minimal >/dev/null; }
echo "== building (Release) =="
scripts/configure.sh . build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)" --target splinecal_tool >/dev/null
sc=build/splinecal
out=demo-out
rm -rf "$out"
mkdir -p "$out"
yaml() { grep -E "^ *$2:" "$1" | head -1 | sed 's/^ *//'; }

echo
echo "== 0. bags: a ROS 2 recording (two .db3 files, data/bags/rosbag2_db3) to EuRoC folders =="
$sc bag info data/bags/rosbag2_db3
$sc bag extract data/bags/rosbag2_db3 --topics /imu0,/cam0/image_raw,/cam1/image_raw \
  --out "$out/from_bag"
head -3 "$out/from_bag/imu0/data.csv"

echo
echo "== 1. detect: AprilGrid corners in a real EuRoC stereo frame (data/euroc_april_frames) =="
$sc detect --images data/euroc_april_frames/cam0,data/euroc_april_frames/cam1 \
  --target data/euroc_april_frames/aprilgrid.yaml --draw --out "$out/detect" 2>&1 | grep -v '\[='
echo "first corners of observations.csv (what calibrate reads):"
head -4 "$out/detect/observations.csv"
echo "(overlays: $out/detect/overlays/cam0/, cam1/)"

echo
echo "== 1b. detect -> intrinsics: OpenCV's 13 sample stereo chessboard pairs (data/opencv_chessboard) =="
$sc detect --images data/opencv_chessboard/cam0,data/opencv_chessboard/cam1 \
  --target data/opencv_chessboard/checkerboard.yaml --quiet --out "$out/detect_chessboard"
$sc intrinsics --observations "$out/detect_chessboard/observations.csv" \
  --target data/opencv_chessboard/checkerboard.yaml --models pinhole-radtan,pinhole-radtan \
  --resolution 640x480 --out "$out/intrinsics" 2>&1 | grep -v iteration
echo "OpenCV's reference for the left camera (k3 fixed at 0): fx fy cx cy 533.052 533.182 342.459 233.915,"
echo "  RMS 0.19667 px (the board's square is 1 unit, so the baseline is in squares)"
echo "(camchain: $out/intrinsics/camchain.yaml, report: $out/intrinsics/report.html)"

echo
echo "== 2. the spline: evaluate the bundled control poses (data/vio_course_spline.csv) =="
$sc evaluate --spline data/vio_course_spline.csv --samples 5 --out "$out/evaluate"

echo
echo "== 3. simulate 20 s of noise-free IMU on the VIO-course trajectory, integrate it =="
$sc simulate --trajectory vio_course --duration 20 --noise-free --quiet --out "$out/simulate"
$sc integrate --imu "$out/simulate/mav0/imu0/data.csv" \
  --groundtruth "$out/simulate/mav0/state_groundtruth_estimate0/data.csv" \
  --method euler,midpoint,rk4 --quiet --out "$out/integrate_sim"
echo "(top view: $out/integrate_sim/trajectory.svg)"

echo
echo "== 3b. Kalibr's IMU models: raw readings of two miscalibrated IMUs, undone by correct =="
$sc simulate --trajectory vio_course --duration 20 --noise-free \
  --imu-intrinsics data/imu_models/two_imus.yaml --quiet --out "$out/simulate_models"
$sc correct --imu "$out/simulate_models/mav0/imu0/data.csv" \
  --imu-intrinsics "$out/simulate_models/imu_models.yaml" --quiet --out "$out/corrected"
python3 - "$out/simulate/mav0/imu0/data.csv" "$out/simulate_models/mav0/imu0/data.csv" \
  "$out/corrected/mav0/imu0/data.csv" <<'PY'
import csv, sys
rows = [list(csv.reader(open(f)))[1:] for f in sys.argv[1:]]
def worst(a, b, cols):
    return max(abs(float(x[c]) - float(y[c])) for x, y in zip(a, b) for c in cols)
for name, cols, unit in (("gyro", (1, 2, 3), "rad/s"), ("accel", (4, 5, 6), "m/s^2")):
    print(f"imu0 {name}: raw off the ideal IMU by up to {worst(rows[0], rows[1], cols):.4f} {unit}, "
          f"corrected by {worst(rows[0], rows[2], cols):.1e} {unit}")
PY
echo
echo "== 4. integrate the first 10 s of real EuRoC V1_01_easy from its ground-truth start =="
$sc integrate --imu data/euroc_v1_01_easy_20s/imu0.csv \
  --groundtruth data/euroc_v1_01_easy_20s/groundtruth.csv --duration 10 --quiet \
  --out "$out/integrate_euroc"

echo
echo "== 5. Allan deviation of a simulated static hour (ADIS16448 noise) =="
printf '0 0 0 0 0 0 0 1\n3600 0 0 0 0 0 0 1\n' > "$out/static_pose.txt"
$sc simulate --trajectory-file "$out/static_pose.txt" --knot-spacing 60 --seed 7 --quiet \
  --out "$out/static" >/dev/null
$sc allan --imu "$out/static/mav0/imu0/data.csv" --quiet --out "$out/allan"
printf '%-30s %14s %14s\n' "Kalibr key" true recovered
for key in gyroscope_noise_density gyroscope_random_walk accelerometer_noise_density \
           accelerometer_random_walk; do
  printf '%-30s %14s %14s\n' "$key" "$(yaml "$out/static/imu.yaml" "$key" | awk '{print $2}')" \
    "$(grep -E "^$key:" "$out/allan/imu.yaml" | awk '{print $2}')"
done
echo "(plot: $out/allan/allan.svg)"

echo
echo "== 6. align up-to-scale camera poses (true scale 1/0.37 = 2.7027) with noisy IMU =="
$sc simulate --trajectory random --duration 10 --seed 3 --quiet --out "$out/simulate_random" >/dev/null
python3 scripts/up_to_scale_camera.py \
  "$out/simulate_random/mav0/state_groundtruth_estimate0/data.csv" 0.37 20 \
  > "$out/camera_up_to_scale.txt" 2> "$out/camera_truth.txt"
# The poses are exact (the simulation's truth, scaled): say so. Align's default 5 mm / 0.002 rad
# would weight the IMU too little and put the scale 1.3% off (docs/align.md, "Uncertainty").
$sc align --imu "$out/simulate_random/mav0/imu0/data.csv" \
  --camera-poses "$out/camera_up_to_scale.txt" --camera-position-std 0.0001 \
  --camera-rotation-std 0.00005 --quiet --out "$out/align"
echo "truth: $(cat "$out/camera_truth.txt")"

echo
echo "== 7. fit: simulated vio_course with constant biases, ADIS16448 white noise =="
$sc simulate --trajectory vio_course --duration 20 --gyro-bias 0.01,-0.02,0.015 \
  --accel-bias 0.1,-0.05,0.08 --gyroscope_random_walk 1e-12 --accelerometer_random_walk 1e-12 \
  --seed 5 --quiet --out "$out/simulate_biased" >/dev/null
$sc fit --imu "$out/simulate_biased/mav0/imu0/data.csv" \
  --poses "$out/simulate_biased/mav0/state_groundtruth_estimate0/data.csv" \
  --imu-yaml "$out/simulate_biased/imu.yaml" --quiet --out "$out/fit_sim"
echo "truth: gyro_bias [0.01 -0.02 0.015] rad/s, accel_bias [0.1 -0.05 0.08] m/s^2"
echo "(report: $out/fit_sim/report.html)"

echo
echo "== 8. fit: the bundled EuRoC V1_01_easy excerpt, ground truth as the pose source =="
$sc fit --imu data/euroc_v1_01_easy_20s/imu0.csv --poses data/euroc_v1_01_easy_20s/groundtruth.csv \
  --imu-yaml data/euroc_v1_01_easy_20s/sensor.yaml --knot-spacing 0.05 --quiet \
  --out "$out/fit_euroc" 2>&1 | grep -v '^warning'
echo "reference (the dataset's estimator, first row): $(awk -F, 'NR==2{printf "gyro_bias [%s %s %s], accel_bias [%s %s %s]", $12,$13,$14,$15,$16,$17}' data/euroc_v1_01_easy_20s/groundtruth.csv)"
echo "(on 20 mostly static seconds the accel bias is weakly separated from gravity; see docs/fit.md)"

echo
echo "== 9. camera-IMU calibration of a simulated rolling-shutter camera (30 s, AprilGrid) =="
$sc simulate --trajectory calibration --duration 30 --camchain data/calibration/camchain_truth.yaml \
  --target data/calibration/aprilgrid.yaml --seed 2 --quiet --out "$out/simulate_camera" >/dev/null
$sc calibrate --imu "$out/simulate_camera/mav0/imu0/data.csv" \
  --observations "$out/simulate_camera/observations.csv" \
  --camchain data/calibration/camchain_guess.yaml --target data/calibration/aprilgrid.yaml \
  --imu-yaml "$out/simulate_camera/imu.yaml" --rolling-shutter --threads "$(nproc)" --quiet \
  --out "$out/calibrate"
echo "truth (data/calibration/camchain_truth.yaml): translation [0.06 -0.02 0.01] m,"
echo "  timeshift_cam_imu 4.2 ms, line_delay 30 us/row; the start was 2.9 deg and 2.7 cm off"
echo "(report: $out/calibrate/report.html)"
echo
echo "== 10. the calibration exported for OpenVINS (docs/export.md) =="
$sc export --from "$out/calibrate" --format openvins --out "$out/export_openvins"
