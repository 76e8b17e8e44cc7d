# Included by ctest after the discovered GoogleTest cases (tests/CMakeLists.txt): the relative
# cost of the longest tests, so that `ctest -j2` starts them first and the short ones fill the
# other core around them. Without it a fresh build folder (every CI clone) has no
# Testing/Temporary/CTestCostData.txt and ctest starts tests in file order, which can leave the
# longest real-data calibration for the end, alone on one core. After one run ctest's own
# measured costs take over. The figures are wall seconds measured on the loaded shared machine
# (2026-11-28, docs/reliability.md, "Where the time goes" and "CI time in CPU seconds"): a
# ranking, not a budget. Names absent from a build (the sanitizer build has no slow tests) are
# ignored by ctest.
set_tests_properties(IntrinsicsExactLeastSquares.RadTanCam0NoWorseThanOpenCvCalibrateCamera
  PROPERTIES COST 137)
set_tests_properties(IntrinsicsExactLeastSquares.RadTanCam1NoWorseThanOpenCvCalibrateCamera
  PROPERTIES COST 104)
set_tests_properties(
  CalibrateEuroc.WholeRecordingAgreesWithThePublishedCalibrationsFromAPerturbedStart
  PROPERTIES COST 103)
set_tests_properties(IntrinsicsNees.EveryModelInItsNinetyFivePercentBand PROPERTIES COST 93)
set_tests_properties(
  CalibrateOwnChain.DsNonePositionsBaselineAndRotationBesidesThePrincipalPoint
  PROPERTIES COST 76)
set_tests_properties(CalibrateMonteCarlo.DiagonalNeesOnAClosedFormTrajectoryIsInsideItsInterval
  PROPERTIES COST 78)
set_tests_properties(CalibrateEuroc.HalvesAgreeWithinTheirReportedStandardDeviations
  IntrinsicsEuroc.RadTanAgreesWithOpenCvCalibrateCameraOnTheSameCorners PROPERTIES COST 55)
set_tests_properties(IntrinsicsEuroc.DoubleSphereAgainstBasaltsPublishedCalibration
  PROPERTIES COST 47)
set_tests_properties(Calibrate.WideAngleDoubleSphereRoundTrip
  Fit.BiasSplineFollowsADriftingBias IntrinsicsHalves.HalvesOfTheRecordingAgreeWithinTheirStds
  PROPERTIES COST 26)
