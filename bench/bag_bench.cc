// Reading speed of the bag readers (io/bag_reader.h, docs/bags.md and docs/performance.md):
//   - BM_ReadBag/<file>: every message of a recording streamed through BagReader::Next from the
//     page cache (index read included); counter: MB/s of message bytes delivered. The files are
//     the large recordings scripts/make_bench_bags.sh writes (15 s of 752 x 480 mono8 at 20 Hz
//     and a 200 Hz IMU, about 110 MB of messages) in every chunk compression of ROS 1 and MCAP.
//   - BM_ParseAndConvert/<file>: the same plus parsing every message and turning every image to
//     grey (detect/bag_image.h), what `bag extract` does before PNG encoding.
//   - BM_DecodeCompressedImage/<format>: one sensor_msgs/CompressedImage of the bundled real
//     EuRoC frame (752 x 480) decoded to grey, PNG as the dataset stores it and JPEG as OpenCV
//     encodes it at quality 95 (what image_transport's compressed plugin writes by default);
//     counter: frames/s. The decode is what a CompressedImage topic adds over a raw Image.
//
// Run: scripts/make_bench_bags.sh DIR, then SPLINECAL_BENCH_BAGS=DIR build-bench/bench/bag_bench
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "splinecal/detect/bag_image.h"
#include "splinecal/error.h"
#include "splinecal/io/bag_messages.h"
#include "splinecal/io/bag_reader.h"

namespace splinecal {
namespace {

const char* const kFiles[] = {"bench_none.bag",  "bench_bz2.bag",   "bench_lz4.bag",
                              "bench_none.mcap", "bench_zstd.mcap", "bench_lz4.mcap"};

std::string BenchBag(benchmark::State& state, int index) {
  const char* dir = std::getenv("SPLINECAL_BENCH_BAGS");
  const std::string path = std::string(dir == nullptr ? "" : dir) + "/" + kFiles[index];
  if (dir == nullptr || !std::filesystem::exists(path)) {
    state.SkipWithError("set SPLINECAL_BENCH_BAGS to the folder of scripts/make_bench_bags.sh");
  }
  state.SetLabel(kFiles[index]);
  return path;
}

// Streams every message of the benchmark's recording through `use`; reports message bytes/s.
template <typename Use>
void StreamBag(benchmark::State& state, Use use) {
  const std::string path = BenchBag(state, static_cast<int>(state.range(0)));
  int64_t bytes = 0;
  for (auto _ : state) {
    try {
      const std::unique_ptr<BagReader> bag = OpenBag({path});
      BagMessage message;
      while (bag->Next(&message)) {
        bytes += static_cast<int64_t>(message.data.size());
        use(*bag, message);
      }
    } catch (const Error& e) {
      state.SkipWithError(e.what());
      break;
    }
  }
  state.SetBytesProcessed(bytes);
}

void BM_ReadBag(benchmark::State& state) {
  StreamBag(state, [](const BagReader&, const BagMessage& message) {
    benchmark::DoNotOptimize(message.data.data());
  });
}
BENCHMARK(BM_ReadBag)->DenseRange(0, 5)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ParseAndConvert(benchmark::State& state) {
  StreamBag(state, [](const BagReader& bag, const BagMessage& message) {
    const BagTopic& topic = bag.topics()[message.topic];
    if (KindOfType(topic.type) == BagMessageKind::kImu) {
      benchmark::DoNotOptimize(ParseImuMessage(topic, message));
    } else {
      benchmark::DoNotOptimize(BagImageToGray(ParseImageMessage(topic, message), message.where));
    }
  });
}
BENCHMARK(BM_ParseAndConvert)->DenseRange(0, 5)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_DecodeCompressedImage(benchmark::State& state) {
  const bool jpeg = state.range(0) == 1;
  const std::string frame = std::string(SPLINECAL_SOURCE_DIR) +
                            "/data/euroc_april_frames/cam0/data/1403709395937837056.png";
  std::vector<unsigned char> bytes;
  if (jpeg) {
    cv::imencode(".jpg", cv::imread(frame, cv::IMREAD_GRAYSCALE), bytes,
                 {cv::IMWRITE_JPEG_QUALITY, 95});
  } else {
    std::ifstream file(frame, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
  }
  ImageMessage image;
  image.compressed = true;
  image.encoding = jpeg ? "jpeg" : "png";
  image.data = std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  state.SetLabel(image.encoding + ", " + std::to_string(bytes.size()) + " bytes");
  for (auto _ : state) benchmark::DoNotOptimize(BagImageToGray(image, "bench").view());
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DecodeCompressedImage)->ArgName("jpeg")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace splinecal

BENCHMARK_MAIN();
