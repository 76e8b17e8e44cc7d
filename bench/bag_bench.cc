// Reading speed of the bag readers (io/bag_reader.h, docs/bags.md and docs/performance.md):
//   - BM_ReadBag/<file>: every message of a recording streamed through BagReader::Next from the
//     page cache (index read included); counter: MB/s of message bytes delivered. The files are
//     the large recordings scripts/make_bench_bags.sh writes (15 s of 752 x 480 mono8 at 20 Hz
//     and a 200 Hz IMU, about 110 MB of messages) in every chunk compression of ROS 1 and MCAP.
//   - BM_ParseAndConvert/<file>: the same plus parsing every message and turning every image to
//     grey (detect/bag_image.h), what `bag extract` does before PNG encoding.
//
// Run: scripts/make_bench_bags.sh DIR, then SPLINECAL_BENCH_BAGS=DIR build-bench/bench/bag_bench
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <string>

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

}  // namespace
}  // namespace splinecal

BENCHMARK_MAIN();
