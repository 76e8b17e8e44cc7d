# Included by ctest after the discovered GoogleTest cases (tests/CMakeLists.txt): the fast tests
# the sanitizer build does not run (`ctest -LE "slow|sanitize_skip"`, scripts/test.sh
# --sanitize). The Release build runs them all.
#
# The rule (docs/reliability.md, "Which tests run under the sanitizers"): the sanitizers look for
# memory errors and undefined behaviour along a code path, and one run of a path finds what a
# second run of it finds. A fast test is left out of the sanitizer build when all three hold:
#   1. it costs over 10 s under the sanitizers (measured, docs/reliability.md);
#   2. what it asserts is the numbers a long estimation converges to (an accuracy, an iteration
#      count, an agreement between two solves), which the Release build checks;
#   3. a cheaper test that the sanitizer build runs takes the same path through the library
#      and the tool with the same options; it is named beside the entry.
# Tests whose point is a path of their own (a command's files, a report, a reader, the detector,
# bad input) stay, whatever they cost. The second rule: a test whose whole path another
# sanitized test takes with the same input is no path of its own, whatever it asserts: the
# bad-input rows at the end, each the same reader with the same options on the same bad file as
# another command's row (0.41 s each, but 81 of them).
set(SPLINECAL_SANITIZE_SKIP_TESTS
  # A 15 s rolling-shutter calibration on the coupled SE(3) spline. The same options and model
  # run in Calibrate.EstimatedIntrinsicsFromAPerturbedStartWithinThreeStd (10 s, rolling
  # shutter, SE(3), intrinsics estimated on top) and the same test's /split case runs the other
  # trajectory model.
  "Models/CalibrateOfModel.RollingShutterRoundTrip/se3  # GetParam() = se3"
  # Compares the iteration counts of two real-data calibrations (with and without
  # --rolling-shutter). The tool's --rolling-shutter path runs in every CalibrateCommand test
  # (simulated data), the same real window without it in
  # CalibrateCommandRealWindow.EvaluateOnTheSplinePredictsTheAccelerometer.
  "CalibrateCommandRealWindow.RollingShutterOnAGlobalShutterConvergesAsFast"
  # The double-sphere fisheye with 100 landmarks, 8 s (70 s sanitized): an accuracy within the
  # targets and stds. The same model and intrinsics, with landmarks seen through it, run in
  # SimulateCameraCommand.WideAngleDoubleSphereThroughSimulateAndCalibrate (12 s: simulate and
  # calibrate, 4 s, 60 landmarks); the landmark path from initial poses in
  # Calibrate.NaturalLandmarksOnlyFromInitialPosesShortRecording.
  "Calibrate.WideAngleDoubleSphereRoundTrip"
  # Renders 100+ frames, detects them and calibrates on the detections (53 s sanitized): the
  # corners' and the calibration's accuracy. The detector on a folder of frames runs in
  # DetectCommand.FindsEveryCornerOfTheBundledStereoFrame (real EuRoC frames), the renderer and
  # the detector on rendered grids in AprilGridRecall.TwentyPixelTagsOfRenderedGridsGiveExact-
  # Corners, and calibrate on an observations file with the same flags in
  # CalibrateCommand.WritesKalibrCamchainResultAndReport.
  "DetectThenCalibrate.ImagesOfASimulatedRecordingGiveTheRigBack"
  # Two 30 s fits, bias spline against constant bias (36 s sanitized): the residuals' levels.
  # The spline bias model in Fit, with its covariance, runs in
  # Fit.TheThreeCovarianceComputationsAgree (8 s of data, three solves); the kept per-sample
  # residuals in Fit.KeepsPerSampleResidualsForTheReport.
  "Fit.BiasSplineFollowsADriftingBias"
  # Every camera model on 40 views (32 s sanitized): each within 4 of its stds. The same
  # CalibrateIntrinsics path for every model, on 6 views, runs in
  # CalibrateIntrinsicsModels.EveryModelFitsAFewViewsAtThePixelNoise (written for this).
  "CalibrateIntrinsics.EveryModelFromTheSweepWithinThreeStd"
  # Six calibrations of 40 views, three with every target point free (10.0 and 10.6 s
  # sanitized): the intrinsics within 3 std, the offsets' NEES. The same free-target path
  # (a residual block per corner, the gauge, the offsets' covariance, the refined target) runs
  # in IntrinsicsCommand.TargetPointsWritesTheRefinedTarget (7.8 s), through the command.
  "TargetPointsCalibration.RecoversEveryPointAndUnbiasedIntrinsics"
  "TargetPointsCalibration.AnExactTargetComesOutUnmovedAtAPriceInStd"
  # Four 8 s calibrations with free intrinsics, with and without the view clusters (28 s
  # sanitized): how much the stds widen. The view-cluster covariance is on by default
  # (CovarianceOptions::view_clusters) and runs with free intrinsics in
  # Calibrate.EstimatedIntrinsicsFromAPerturbedStartWithinThreeStd; the clusters themselves in
  # ViewClusters.* (intrinsics).
  "CalibrateViewClusters.WidenTheStdsForAModelMisfitNotForAnExactModel"
  # simulate, then calibrate with --rolling-shutter and --imu-yaml (26 s sanitized): the time
  # offset, line delay and lever arm recovered. simulate's files run in
  # SimulateCameraCommand.WritesObservationsAndTruthDeterministically and
  # SimulateCameraCommand.WideAngleDoubleSphereThroughSimulateAndCalibrate (simulate then
  # calibrate); calibrate with --rolling-shutter in every CalibrateCommand test.
  "SimulateCameraCommand.CalibrateRecoversTheSimulatedRig"
  # Two IMUs, the second turned and moved (22 s sanitized): its pose and time offset recovered.
  # Two IMUs through the same calibration run in CalibrateImus.UndeterminedLeverArmHeldWith-
  # AWarning (9 s) and, through the tool with its files, in
  # CalibrateCommand.SeveralImusWriteEachImu.
  "CalibrateImus.TwoImusRoundTrip"
  # The strided Allan kernel against a direct sum over 300,001 samples (15 s sanitized): an
  # agreement to 1e-12, arithmetic the Release build checks. The same strided kernel, with the
  # budget's strides on 1,000,000 samples, runs in
  # StridedAllanDeviation.ExactCurveLiesWithinTheStridedIntervals (1 s).
  "StridedAllanDeviation.EqualsDirectStridedSum"
  # A fit of the EuRoC V1_01_easy recording (12 s sanitized): its biases and gravity against the
  # ground truth. The same files are read in ReadEurocGroundTruth.SharedRealDataReads, and Fit
  # with its options in every Fit.* test (simulated data).
  "FitEuroc.V101EasyBiasesMatchTheGroundTruth"
  # The coarse-to-fine initial sweep against the exhaustive one, 8 models x 2 seeds (2.5 s in
  # Release, 45 s sanitized): an agreement between two searches over the same scores. The
  # coarse-to-fine sweep, Score's early exit and every model's PnP run sanitized in
  # CalibrateIntrinsicsModels.EveryModelFitsAFewViewsAtThePixelNoise (every model, started by
  # the sweep) and CompareModels.*.
  "InitialIntrinsics.CoarseToFinePicksTheExhaustiveCandidateForEveryModel"
  # Nine simulated cameras unlike EuRoC's through the sweep and the solve (0.9 CPU-s in Release,
  # 12.6 s sanitized in the fresh-clone CI run of 590e6ba): accuracies. The sweep (its choice of
  # views by depth spread, the coarse-to-fine grid) and the solve run sanitized for every model in
  # CalibrateIntrinsicsModels.EveryModelFitsAFewViewsAtThePixelNoise, and the grid-edge warning
  # in InitialIntrinsicsCameras.ALensBeyondTheGridIsNamed.
  "InitialIntrinsicsCameras.TheSweepAndTheSolveFindEveryCamera"
  # Three 8 s calibrations, the intrinsics held, with a prior and free (17.1 s sanitized in the
  # warm CI run of 6d42b6a; 20.4 CPU-s): how the stds order. Each mode's path runs sanitized
  # (calib/calibrate.cc, ResolveIntrinsicsModes): the prior, on the same scenario and prior, in
  # Calibrate.APriorTheDataPullAgainstKeepsItsPosteriorBelowItsStd (6 s; a covariance and no
  # mode given: kPrior); free in Calibrate.EstimatedIntrinsicsFromAPerturbedStartWithinThreeStd
  # (estimate_intrinsics: kFree); held in every other Calibrate test (no covariance: kHeld); the
  # refusal of a prior without a covariance in CalibrateRefuses.AnIntrinsicsPriorWithoutA-
  # Covariance (written for this, 1.5 CPU-s sanitized).
  "Calibrate.IntrinsicsPriorBetweenHeldAndFree"
  # Three 8 s calibrations with the target-scale check (19.9 s sanitized in that run; 27.2
  # CPU-s): the scale's std and the 1.47x refusal's figures. The check's solve, covariance and
  # refusal message run on 4 s in CalibrateRefuses.ATargetTheImuSaysIsOfAnotherSize (written
  # for this, 4.4 CPU-s sanitized); the check passing and held at 1 in every CalibrateCommand
  # test (the tool's default --target-scale check, e.g.
  # CalibrateCommand.WritesKalibrCamchainResultAndReport); a wrong target held unchecked in
  # CalibrateRefuses.ATargetOfTheWrongSizeIsNotAConfidentAnswer.
  "Calibrate.TargetScaleAgainstTheImu")
# The bad-input table's rows (tests/cli/bad_input_test.cc) whose reader, with the same options,
# the same bad file and the same valid other files, another command's row runs: each row starts
# a sanitized test and a sanitized tool, 0.41 s in the warm CI run of 6d42b6a, and 81 rows are
# left out here (about 33 s sanitized). A row is the reader's path on one bad class; the tool's
# own error handling is the same main() for every command, and each command keeps rows of its
# own (its other files, MissingFile, Directory, UnwritableOutput). Read in src/cli/*_command.cc:
#   fit_imu_* and align_imu_*: ReadEurocImu(path, ImuReadOptionsFromFlags(true)), as
#     calibrate_imu_* (ReadRigImus; integrate_imu_* runs the reader without the imu.yaml hint);
#   align_imu_yaml_* and simulate_imu_yaml_*: ReadImuYaml(FLAGS_imu_yaml), as fit_imu_yaml_*;
#   align_camera_poses_*, simulate_trajectory_file_*, calibrate_initial_poses_*: ReadPoses(path),
#     as fit_poses_* (the same FileRole defaults, so the same classes and messages).
# Each row still runs in the Release build.
# (Indented by four: tests/CMakeLists.txt reads the names above from lines indented by two.)
set(splinecal_duplicate_reader_rows
    "/(fit_imu|align_imu)_[A-Z]"
    "/(align|simulate)_imu_yaml_"
    "/(align_camera_poses|simulate_trajectory_file|calibrate_initial_poses)_")
foreach(splinecal_row ${cli_tests_TESTS})
  if(NOT splinecal_row MATCHES "^EveryCommand/BadInput\\.ExitsTwoWithOneLineAndWritesNothing/")
    continue()
  endif()
  foreach(splinecal_pattern ${splinecal_duplicate_reader_rows})
    if(splinecal_row MATCHES "${splinecal_pattern}")
      list(APPEND SPLINECAL_SANITIZE_SKIP_TESTS "${splinecal_row}")
      break()
    endif()
  endforeach()
endforeach()
foreach(splinecal_skipped_test ${SPLINECAL_SANITIZE_SKIP_TESTS})
  # One label per test as ctest reads it; "fast" stays for `ctest -L fast`.
  set_tests_properties("${splinecal_skipped_test}" PROPERTIES LABELS "fast;sanitize_skip")
endforeach()
