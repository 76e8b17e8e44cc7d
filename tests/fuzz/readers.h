// Every file reader of splinecal, by name: what the reader fuzz targets (tests/fuzz/<name>_fuzz.cc)
// and the corpus regression test (tests/io/fuzz_corpus_test.cc) call on each input.
//
// A reader passes an input when it returns or throws splinecal::Error. Where a reader has a
// writer, what it read must also survive the writer and read back the same (the property is
// checked here, so that the fuzzer finds writer bugs too); a broken property throws
// std::logic_error, which the fuzz target does not catch (a finding) and the test reports.
#ifndef SPLINECAL_TESTS_FUZZ_READERS_H_
#define SPLINECAL_TESTS_FUZZ_READERS_H_

#include <cstdint>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzz_input.h"
#include "splinecal/detect/bag_image.h"
#include "splinecal/detect/image_file.h"
#include "splinecal/detect/target_detector.h"
#include "splinecal/error.h"
#include "splinecal/io/bag_messages.h"
#include "splinecal/io/bag_reader.h"
#include "splinecal/io/camchain_yaml.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/imu_models_yaml.h"
#include "splinecal/io/kalibr_yaml.h"
#include "splinecal/io/observations_csv.h"
#include "splinecal/io/poses.h"
#include "splinecal/io/spline_csv.h"
#include "splinecal/io/static_recording.h"
#include "splinecal/io/target_yaml.h"
#include "splinecal/io/yaml_document.h"

namespace splinecal {
namespace fuzz {

struct Reader {
  const char* name;  // the fuzz target is <name>_fuzz
  const char* suffix;
  void (*read)(const std::string& path);
};

inline void Expect(bool property, const std::string& what) {
  if (!property) throw std::logic_error("property broken: " + what);
}

// Writes `text` to a second temporary file and returns its path (for read-back checks).
inline std::string WriteText(const std::string& text, const char* suffix) {
  const std::string path = TempPath(std::string("readback") + suffix);
  WriteFileOrTrap(path, text.data(), text.size());
  return path;
}

// Calls `reader`, swallowing splinecal::Error (the reader refused the input, as it should).
template <typename Function>
void Refusable(Function reader) {
  try {
    reader();
  } catch (const Error&) {
  }
}

// The generic YAML lookups every YAML reader is built on, on whatever keys the file has.
inline void ReadYamlKeys(const std::string& path) {
  const YamlDocument yaml(path);
  for (const std::string& key : yaml.TopLevelKeys()) {
    Refusable([&] { yaml.Rows(key); });
    Refusable([&] { yaml.Numbers(key); });
    Refusable([&] { yaml.String(key); });
    Refusable([&] { yaml.Integer(key); });
  }
  Refusable([&] { yaml.Rows("cam0/T_cam_imu"); });
}

inline void ReadImuYamlAndKeys(const std::string& path) {
  Refusable([&] { ReadImuYaml(path); });
  ReadYamlKeys(path);
}

// An image file through the decoders and, when it decodes, through the AprilGrid detector (one
// detector for all inputs: building its decode table takes 20 ms).
inline void ReadImageAndDetect(const std::string& path) {
  const GrayImage image = ReadGrayImage(path);
  static TargetDetector* detector = new TargetDetector(MakeAprilGrid(6, 6, 0.088, 0.3));
  const TargetDetection detection = detector->Detect(image.view());
  for (const CornerDetection& corner : detection.corners) {
    Expect(corner.uv.x() >= 0 && corner.uv.y() >= 0 && corner.uv.x() <= image.width - 1 &&
               corner.uv.y() <= image.height - 1,
           "a detected corner lies inside the image");
  }
}

inline void ReadObservationsRoundTrip(const std::string& path) {
  const std::vector<Observation> observations = ReadObservationsCsv(path);
  std::ostringstream text;
  WriteObservationsCsv(observations, &text);
  const std::vector<Observation> again = ReadObservationsCsv(WriteText(text.str(), ".csv"));
  Expect(again.size() == observations.size(), "observations read back: same count");
  for (size_t i = 0; i < again.size(); ++i) {
    const Observation& a = observations[i];
    const Observation& b = again[i];
    Expect(a.t_ns == b.t_ns && a.cam_id == b.cam_id && a.point_id == b.point_id && a.uv == b.uv,
           "observations read back exactly");
  }
}

inline void ReadCamchainRoundTrip(const std::string& path) {
  const Camchain camchain = ReadCamchainYaml(path);
  const Camchain again = ReadCamchainYaml(WriteText(CamchainYamlText(camchain), ".yaml"));
  Expect(again.size() == camchain.size(), "camchain read back: same cameras");
  for (size_t i = 0; i < again.size(); ++i) {
    const CameraCalibration& a = camchain[i];
    const CameraCalibration& b = again[i];
    Expect(a.camera.intrinsics() == b.camera.intrinsics() &&
               a.camera.projection == b.camera.projection &&
               a.camera.distortion == b.camera.distortion &&
               a.camera.radtan_k3 == b.camera.radtan_k3 && a.camera.width == b.camera.width &&
               a.camera.height == b.camera.height && a.time_offset_s == b.time_offset_s &&
               a.line_delay_s == b.line_delay_s && a.rostopic == b.rostopic,
           "camchain read back exactly");
    // The rotation goes through a quaternion each way: equal to rounding.
    Expect((a.T_cam_imu.matrix() - b.T_cam_imu.matrix()).cwiseAbs().maxCoeff() <=
               1e-12 * (1.0 + a.T_cam_imu.translation().norm()),
           "camchain T_cam_imu read back");
  }
}

// Kalibr's IMU result file (io/imu_models_yaml.h): what it reads, written and read again, is the
// same calibration.
inline void ReadImuModelsRoundTrip(const std::string& path) {
  const std::vector<ImuCalibration> imus = ReadImuModelsYaml(path);
  const std::vector<ImuCalibration> again =
      ReadImuModelsYaml(WriteText(ImuModelsYamlText(imus), ".yaml"));
  Expect(again.size() == imus.size(), "imu models read back: same IMUs");
  for (size_t i = 0; i < again.size(); ++i) {
    const ImuIntrinsicsd& a = imus[i].intrinsics;
    const ImuIntrinsicsd& b = again[i].intrinsics;
    Expect(imus[i].model == again[i].model && imus[i].time_offset_s == again[i].time_offset_s &&
               a.M_a == b.M_a && a.M_g == b.M_g && a.A == b.A && a.ry_i == b.ry_i &&
               a.rz_i == b.rz_i,
           "imu models read back exactly");
    // Rotations go through a quaternion each way, r_b through T_i_b: equal to rounding.
    Expect((a.C_i_b - b.C_i_b).cwiseAbs().maxCoeff() <= 1e-12 &&
               (a.C_gyro_i - b.C_gyro_i).cwiseAbs().maxCoeff() <= 1e-12 &&
               (a.r_b - b.r_b).cwiseAbs().maxCoeff() <= 1e-12 * (1.0 + a.r_b.norm()),
           "imu models rotations and r_b read back");
  }
}

inline void ReadTargetRoundTrip(const std::string& path) {
  const CalibrationTarget target = ReadTargetYaml(path);
  const CalibrationTarget again = ReadTargetYaml(WriteText(TargetPointsYamlText(target), ".yaml"));
  Expect(again.points == target.points, "target points read back exactly");
}

inline void ReadSplineRoundTrip(const std::string& path) {
  const SE3Splined spline = ReadSplineCsv(path);
  std::ostringstream text;
  WriteSplineCsv(spline, &text);
  const SE3Splined again = ReadSplineCsv(WriteText(text.str(), ".csv"));
  Expect(again.num_control_poses() == spline.num_control_poses() &&
             again.t0_ns() == spline.t0_ns() && again.dt_ns() == spline.dt_ns(),
         "spline read back: same layout");
  for (int i = 0; i < spline.num_control_poses(); ++i) {
    Expect(again.control_pose(i).matrix() == spline.control_pose(i).matrix(),
           "spline control poses read back bit-exactly");
  }
  // The whole valid range evaluates (what `splinecal evaluate` does next).
  spline.PoseNs(spline.start_time_ns());
  spline.PoseNs(spline.end_time_ns());
}

// allan's own readers. The parallel path for large EuRoC files is forced on (it is meant to give
// the same numbers as the line-by-line path, or to hand the file over to it), and the column
// reader is tried with each sensor choice.
inline void ReadStaticRecordings(const std::string& path) {
  std::optional<StaticRecording> serial;
  StaticReadOptions options;
  options.parallel_min_bytes = INT64_MAX;
  Refusable([&] { serial = ReadEurocStaticRecording(path, options); });
  options.parallel_min_bytes = 0;
  std::optional<StaticRecording> parallel;
  Refusable([&] { parallel = ReadEurocStaticRecording(path, options); });
  Expect(serial.has_value() == parallel.has_value(), "allan: both EuRoC paths accept or refuse");
  if (serial.has_value()) {
    Expect(serial->rate_hz == parallel->rate_hz, "allan: both EuRoC paths give the same rate");
    for (size_t a = 0; a < serial->axes.size(); ++a) {
      Expect(serial->axes[a].samples == parallel->axes[a].samples,
             "allan: both EuRoC paths give the same samples");
    }
  }
  for (const std::optional<ImuSensor>& sensor :
       {std::optional<ImuSensor>(),
        std::optional<ImuSensor>(ImuSensor::kGyroscope),
        std::optional<ImuSensor>(ImuSensor::kAccelerometer)}) {
    Refusable([&] { ReadColumnStaticRecording(path, 200.0, sensor); });
  }
}

// A bag of any format (io/bag_reader.h, told apart by its bytes): every message read, the IMU
// and image ones parsed and the images turned to grey, as `splinecal bag extract` does. A bag
// that reads must list every message it then serves.
inline void ReadBagWhole(const std::string& path) {
  const std::unique_ptr<BagReader> bag = OpenBag({path});
  int64_t listed = 0;
  for (const BagTopic& topic : bag->topics()) listed += topic.message_count;
  int64_t served = 0;
  BagMessage message;
  while (bag->Next(&message)) {
    ++served;
    const BagTopic& topic = bag->topics()[message.topic];
    const BagMessageKind kind = KindOfType(topic.type);
    if (kind == BagMessageKind::kImu) ParseImuMessage(topic, message);
    if (kind == BagMessageKind::kImage || kind == BagMessageKind::kCompressedImage) {
      BagImageToGray(ParseImageMessage(topic, message), message.where);
    }
  }
  Expect(served == listed, "bag: serves every message it lists");
}

inline const std::vector<Reader>& Readers() {
  static const std::vector<Reader> readers = {
      {"euroc_imu", ".csv", [](const std::string& p) { ReadEurocImu(p); }},
      {"euroc_groundtruth", ".csv", [](const std::string& p) { ReadEurocGroundTruth(p); }},
      // fit --poses, align --camera-poses, calibrate --initial-poses, simulate --trajectory-file.
      {"poses", ".txt", [](const std::string& p) { ReadPoses(p); }},
      {"imu_yaml", ".yaml", ReadImuYamlAndKeys},
      {"observations_csv", ".csv", ReadObservationsRoundTrip},
      {"camchain_yaml", ".yaml", ReadCamchainRoundTrip},
      {"imu_models_yaml", ".yaml", ReadImuModelsRoundTrip},
      {"target_yaml", ".yaml", ReadTargetRoundTrip},
      {"spline_csv", ".csv", ReadSplineRoundTrip},
      {"static_recording", ".csv", ReadStaticRecordings},
      {"image_file", ".png", ReadImageAndDetect},
      {"bag", ".bag", ReadBagWhole},
  };
  return readers;
}

// Runs the reader `name` on one fuzz input; unknown names are the harness's fault.
inline void FuzzReader(const std::string& name, const uint8_t* data, size_t size) {
  for (const Reader& reader : Readers()) {
    if (name != reader.name) continue;
    const std::string path = WriteInput(data, size, reader.suffix);
    Refusable([&] { reader.read(path); });
    return;
  }
  __builtin_trap();
}

}  // namespace fuzz
}  // namespace splinecal

// The whole body of a reader fuzz target.
#define SPLINECAL_READER_FUZZER(name)                                       \
  extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) { \
    splinecal::fuzz::FuzzReader(name, data, size);                          \
    return 0;                                                               \
  }

#endif  // SPLINECAL_TESTS_FUZZ_READERS_H_
