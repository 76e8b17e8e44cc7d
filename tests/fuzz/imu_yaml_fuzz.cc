// Fuzzes YAML loading (io/yaml_document.h) through the Kalibr imu.yaml reader, and the generic
// lookups every YAML reader uses.
#include "fuzz_input.h"
#include "splinecal/error.h"
#include "splinecal/io/kalibr_yaml.h"
#include "splinecal/io/yaml_document.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string& path = splinecal::fuzz::WriteInput(data, size, ".yaml");
  try {
    splinecal::ReadImuYaml(path);
  } catch (const splinecal::Error&) {
  }
  try {
    const splinecal::YamlDocument yaml(path);
    for (const std::string& key : yaml.TopLevelKeys()) {
      try {
        yaml.Rows(key);
      } catch (const splinecal::Error&) {
      }
      try {
        yaml.String(key);
      } catch (const splinecal::Error&) {
      }
    }
    yaml.Rows("cam0/T_cam_imu");
  } catch (const splinecal::Error&) {
  }
  return 0;
}
