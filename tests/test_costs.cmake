# Included by ctest after the discovered GoogleTest cases (tests/CMakeLists.txt): the relative
# cost of the longest tests, so that `ctest -j2` starts them first and the short ones fill the
# other core around them. Without it a fresh build folder (every CI clone) has no
# Testing/Temporary/CTestCostData.txt and ctest starts tests in file order, which can leave the
# longest real-data calibration for the end, alone on one core. After one run ctest's own
# measured costs take over. The figures are wall seconds measured on the loaded shared machine
# (2026-11-28, docs/reliability.md, "Where the time goes" and "CI time in CPU seconds"): a
# ranking, not a budget. Names absent from a build (the sanitizer build has no slow tests) are
# ignored by ctest. The sanitizer build has its own ranking (sanitized costs differ: the
# command tests start a sanitized tool), chosen by SPLINECAL_TESTS_SANITIZED, which the
# generated test_build_kind.cmake sets just before this file is read.
if(SPLINECAL_TESTS_SANITIZED)
  # Seconds of each test in the sanitizer build of the 2026-11-28 10:42 CI run
  # (build-sanitize/Testing/Temporary/CTestCostData.txt, docs/reliability.md, "Where the time
  # went on 2026-11-28"); the two landmark tests, which an allocation pattern (since fixed)
  # made 30 to 60 times slower there, at their CPU-s with ASan's allocator preloaded into the
  # Release test program after the fix.
  set_tests_properties(DetectThenCalibrate.ImagesOfASimulatedRecordingGiveTheRigBack
    PROPERTIES COST 56)
  set_tests_properties(CalibrateCommand.ImuModelWritesKalibrsImuFileAndTheStds PROPERTIES COST 48)
  set_tests_properties(Fit.BiasSplineFollowsADriftingBias PROPERTIES COST 44)
  set_tests_properties(CalibrateCommandRealWindow.EvaluateOnTheSplinePredictsTheAccelerometer
    Calibrate.EstimatedIntrinsicsFromAPerturbedStartWithinThreeStd
    CalibrateIntrinsics.EveryModelFromTheSweepWithinThreeStd PROPERTIES COST 30)
  set_tests_properties("Models/CalibrateOfModel.RollingShutterRoundTrip/split  # GetParam() = split"
    Calibrate.TargetScaleAgainstTheImu SimulateCameraCommand.CalibrateRecoversTheSimulatedRig
    Calibrate.IntrinsicsPriorBetweenHeldAndFree PROPERTIES COST 26)
  set_tests_properties(CalibrateCommandRealData.CameraWithoutObservationsRefusedAndSelectable
    CalibrateCommand.WritesKalibrCamchainResultAndReport
    StridedAllanDeviation.EqualsDirectStridedSum
    SimulateCameraCommand.WideAngleDoubleSphereThroughSimulateAndCalibrate
    Calibrate.AHeldCameraChainRidesOnCameraZerosExtrinsic CalibrateCommand.QuietSilencesProgress
    CompareModels.TheTrueModelFitsBestOnTheSameCorners PROPERTIES COST 17)
  set_tests_properties(Calibrate.WideAngleDoubleSphereRoundTrip PROPERTIES COST 67)
  set_tests_properties(Calibrate.NaturalLandmarksOnlyFromInitialPosesShortRecording
    PROPERTIES COST 20)
else()
  # Release.
  # The two radtan OpenCV comparisons (137 and 104 before OpenCV's steps were solved by LU),
  # IntrinsicsNees (93 before its solves started from the truth) and FitMonteCarlo's 120 seeds:
  # their CPU-s of 2026-11-28 17:46-18:12 (docs/reliability.md, "Test time before / after")
  # times 2.8, the ratio of the figures here to CPU-s before.
  set_tests_properties(IntrinsicsExactLeastSquares.RadTanCam0NoWorseThanOpenCvCalibrateCamera
    PROPERTIES COST 17)
  set_tests_properties(IntrinsicsExactLeastSquares.RadTanCam1NoWorseThanOpenCvCalibrateCamera
    IntrinsicsEuroc.RadTanAgreesWithOpenCvCalibrateCameraOnTheSameCorners PROPERTIES COST 11)
  set_tests_properties(
    FitMonteCarlo.GravityTimeOffsetAndExtrinsicNeesOnAClosedFormTrajectory PROPERTIES COST 100)
  set_tests_properties(IntrinsicsNees.EveryModelInItsNinetyFivePercentBand PROPERTIES COST 23)
  set_tests_properties(
    CalibrateEuroc.WholeRecordingAgreesWithThePublishedCalibrationsFromAPerturbedStart
    PROPERTIES COST 103)
  set_tests_properties(
    CalibrateOwnChain.DsNonePositionsBaselineAndRotationBesidesThePrincipalPoint
    PROPERTIES COST 76)
  set_tests_properties(CalibrateMonteCarlo.DiagonalNeesOnAClosedFormTrajectoryIsInsideItsInterval
    PROPERTIES COST 78)
  set_tests_properties(CalibrateEuroc.HalvesAgreeWithinTheirReportedStandardDeviations
    PROPERTIES COST 55)
  set_tests_properties(
    IntrinsicsEuroc.StereoBaselineAndDoubleSphereAgainstThePublishedCalibrations
    PROPERTIES COST 47)
  set_tests_properties(Calibrate.WideAngleDoubleSphereRoundTrip
    Fit.BiasSplineFollowsADriftingBias IntrinsicsHalves.HalvesOfTheRecordingAgreeWithinTheirStds
    PROPERTIES COST 26)
endif()
