#include "splinecal/allan/allan.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>

#include "splinecal/allan/detail/sensor_units.h"
#include "splinecal/axis_name.h"
#include "splinecal/error.h"
#include "splinecal/string_printf.h"

namespace splinecal {
namespace {

// The noise fit needs a curve: fewer averaging times than this is refused as too short.
constexpr int kMinAveragingTimes = 3;

// Combines one key over the axes of `sensor`: the identified axes only; when none is, the
// largest of the axes' upper bounds (the mean of bounds would not bound every axis).
KalibrKey Combine(const std::vector<AxisAllan>& axes,
                  ImuSensor sensor,
                  NoiseTerm term,
                  CombineAxes combine,
                  bool unreliable) {
  KalibrKey key;
  std::vector<double> identified;
  double largest_bound = 0.0;
  for (const AxisAllan& axis : axes) {
    if (axis.sensor != sensor) continue;
    key.present = true;
    const TermEstimate& estimate = axis.fit[term];
    largest_bound = std::max(largest_bound, estimate.upper_bound);
    if (!estimate.identified) continue;
    identified.push_back(estimate.value);
    key.axes += std::string(key.axes.empty() ? "" : ", ") + AxisName(axis.axis);
  }
  if (!key.present) return key;
  key.unreliable = unreliable;
  key.num_axes = static_cast<int>(identified.size());
  key.upper_bound = identified.empty();
  if (key.upper_bound) {
    key.value = largest_bound;
  } else if (combine == CombineAxes::kMax) {
    key.value = *std::max_element(identified.begin(), identified.end());
  } else {
    double sum = 0.0;
    for (const double v : identified) sum += v;
    key.value = sum / static_cast<double>(identified.size());
  }
  return key;
}

// Keeps samples [first, last) of every axis.
void Cut(int64_t first, int64_t last, StaticRecording* recording) {
  for (AxisSeries& axis : recording->axes) {
    axis.samples.erase(axis.samples.begin() + last, axis.samples.end());
    axis.samples.erase(axis.samples.begin(), axis.samples.begin() + first);
  }
}

// The progress line on the work budget: how many passes the averaging times take, and where
// they are strided.
std::string BudgetSummary(int64_t n,
                          const std::vector<int64_t>& sizes,
                          const std::vector<int64_t>& strides,
                          double rate_hz) {
  int64_t overlapping = 0;
  int64_t used = 0;
  int64_t smallest = 0;
  int64_t largest = 1;
  double strided_up_to_s = 0.0;
  for (size_t i = 0; i < sizes.size(); ++i) {
    overlapping += AllanTermCount(n, sizes[i], 1);
    used += AllanTermCount(n, sizes[i], strides[i]);
    if (strides[i] == 1) continue;
    smallest = smallest == 0 ? strides[i] : std::min(smallest, strides[i]);
    largest = std::max(largest, strides[i]);
    strided_up_to_s = std::max(strided_up_to_s, sizes[i] / rate_hz);
  }
  const double passes = static_cast<double>(overlapping) / static_cast<double>(n);
  if (largest == 1) {
    return StringPrintf("allan: %zu averaging times, %.4g passes per axis, all fully overlapping",
                        sizes.size(),
                        passes);
  }
  const std::string stride_range =
      smallest == largest ? std::to_string(smallest)
                          : std::to_string(smallest) + " to " + std::to_string(largest);
  return StringPrintf(
      "allan: %zu averaging times would take %.4g passes per axis; within the budget "
      "(--max-passes) they take %.4g: those up to %.3g s use every s-th start index, s = %s",
      sizes.size(),
      passes,
      static_cast<double>(used) / static_cast<double>(n),
      strided_up_to_s,
      stride_range.c_str());
}

}  // namespace

int64_t MinimumSamplesForAveragingTimes(int count, int taus_per_decade, double max_tau_fraction) {
  int64_t low = 1;  // too few
  int64_t high = 2;
  while (static_cast<int>(AllanClusterSizes(high, taus_per_decade, max_tau_fraction).size()) <
         count) {
    low = high;
    high *= 2;
  }
  while (high - low > 1) {
    const int64_t middle = low + (high - low) / 2;
    if (static_cast<int>(AllanClusterSizes(middle, taus_per_decade, max_tau_fraction).size()) >=
        count) {
      high = middle;
    } else {
      low = middle;
    }
  }
  return high;
}

AllanResult ComputeAllan(StaticRecording&& recording, const AllanOptions& options) {
  const std::string& source = recording.source;
  auto fail = [&](const std::string& message) -> Error {
    return source.empty() ? Error(message) : Error(source, 0, message);
  };
  if (recording.axes.empty()) throw fail("no axes to analyse");
  if (!(std::isfinite(recording.rate_hz) && recording.rate_hz > 0.0)) {
    throw fail("sample rate must be positive and finite, got " + std::to_string(recording.rate_hz) +
               " Hz");
  }
  int64_t n = static_cast<int64_t>(recording.axes.front().samples.size());
  for (const AxisSeries& axis : recording.axes) {
    if (static_cast<int64_t>(axis.samples.size()) != n) {
      throw fail("axes have different lengths (" + std::to_string(n) + " and " +
                 std::to_string(axis.samples.size()) + " samples)");
    }
  }
  // The stretch [start_s, end_s), by sample index at the mean rate.
  if (!(options.start_s >= 0.0) || !(options.end_s > options.start_s)) {
    throw fail(StringPrintf(
        "--start %g s, --end %g s: expected 0 <= start < end", options.start_s, options.end_s));
  }
  const double duration_s = static_cast<double>(n) / recording.rate_hz;
  if (options.start_s >= duration_s) {
    throw fail(
        StringPrintf("--start %g s is beyond the recording's %.6g s", options.start_s, duration_s));
  }
  const int64_t first = std::llround(std::ceil(options.start_s * recording.rate_hz - 1e-9));
  const int64_t last =
      std::isfinite(options.end_s)
          ? std::min<int64_t>(n, std::llround(std::floor(options.end_s * recording.rate_hz + 1e-9)))
          : n;
  if (first > 0 || last < n) Cut(first, last, &recording);
  n = last - first;

  const MotionCheck motion = CheckMotion(recording, options.motion);
  if (motion.moving && options.motion_policy == MotionPolicy::kRefuse) {
    throw fail("the recording is not static: " + motion.Summary(options.motion) +
               ". Cut a static stretch with --start/--end, or pass --allow-motion to mark every "
               "term unreliable");
  }

  std::vector<int64_t> sizes;
  try {
    sizes = AllanClusterSizes(n, options.taus_per_decade, options.max_tau_fraction);
  } catch (const Error& e) {
    throw fail(e.message());
  }
  if (static_cast<int>(sizes.size()) < kMinAveragingTimes) {
    const int64_t needed = MinimumSamplesForAveragingTimes(
        kMinAveragingTimes, options.taus_per_decade, options.max_tau_fraction);
    throw fail(StringPrintf(
        "too few samples for the averaging times: %lld samples (%.4g s at %.6g Hz) give "
        "%d averaging time(s) up to %g of the record; the noise fit needs at least %d, "
        "i.e. at least %lld samples",
        static_cast<long long>(n),
        n / recording.rate_hz,
        recording.rate_hz,
        static_cast<int>(sizes.size()),
        options.max_tau_fraction,
        kMinAveragingTimes,
        static_cast<long long>(needed)));
  }

  std::vector<int64_t> strides;
  try {
    strides = AllanStrides(n, sizes, options.max_passes);
  } catch (const Error& e) {
    throw fail(e.message());
  }
  if (options.progress) options.progress(BudgetSummary(n, sizes, strides, recording.rate_hz));

  AllanResult result;
  result.source = source;
  result.rate_hz = recording.rate_hz;
  result.num_samples = n;
  result.taus_per_decade = options.taus_per_decade;
  result.max_tau_fraction = options.max_tau_fraction;
  result.max_passes = options.max_passes;
  result.combine = options.combine;
  result.start_s = static_cast<double>(first) / recording.rate_hz;
  result.end_s = static_cast<double>(last) / recording.rate_hz;
  result.motion = motion;
  const size_t num_axes = recording.axes.size();
  result.axes.resize(num_axes);
  std::vector<std::exception_ptr> errors(num_axes);
  std::atomic<size_t> next{0};
  std::mutex progress_mutex;
  // The fit's relative intervals depend only on N, the averaging times and their strides: one
  // table for every axis, made by the first thread that needs it.
  std::once_flag intervals_once;
  std::optional<FitIntervals> intervals;
  // Axes run in parallel; threads left over (fewer axes than threads) split each axis's passes.
  const int total_threads =
      options.num_threads > 0 ? options.num_threads
                              : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int threads = std::min<int>(total_threads, static_cast<int>(num_axes));
  const int threads_per_axis = std::max(1, total_threads / threads);
  auto work = [&]() {
    std::vector<double> scratch;  // the strided sums' window, reused by this thread's next axis
    for (size_t a = next++; a < num_axes; a = next++) {
      AxisSeries& series = recording.axes[a];
      AxisAllan& axis = result.axes[a];
      axis.sensor = series.sensor;
      axis.axis = series.axis;
      axis.name = series.name();
      try {
        const IntegratedSignal signal(std::move(series.samples), recording.rate_hz, axis.name);
        axis.mean = signal.mean();
        axis.curve = signal.Deviation(sizes, strides, threads_per_axis, &scratch);
        std::call_once(intervals_once, [&] { intervals.emplace(n, sizes, strides, options.fit); });
        axis.fit = FitNoise(axis.curve, options.fit, &*intervals);
      } catch (...) {
        errors[a] = std::current_exception();
        continue;
      }
      if (options.progress) {
        const std::lock_guard<std::mutex> lock(progress_mutex);
        options.progress("allan: " + axis.name + " done (" + std::to_string(sizes.size()) +
                         " averaging times, " + StringPrintf("%.3g", axis.curve.tau_s.front()) +
                         " to " + StringPrintf("%.3g", axis.curve.tau_s.back()) + " s)");
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& thread : pool) thread.join();
  // The first failing axis in input order, so that the message does not depend on timing.
  for (size_t a = 0; a < num_axes; ++a) {
    if (!errors[a]) continue;
    try {
      std::rethrow_exception(errors[a]);
    } catch (const Error& e) {
      if (source.empty() || !e.path().empty()) throw;
      throw Error(source, 0, e.message());
    }
  }

  const bool unreliable = motion.moving;
  result.gyroscope_noise_density =
      Combine(result.axes, ImuSensor::kGyroscope, NoiseTerm::kWhite, options.combine, unreliable);
  result.gyroscope_random_walk = Combine(
      result.axes, ImuSensor::kGyroscope, NoiseTerm::kRandomWalk, options.combine, unreliable);
  result.accelerometer_noise_density = Combine(
      result.axes, ImuSensor::kAccelerometer, NoiseTerm::kWhite, options.combine, unreliable);
  result.accelerometer_random_walk = Combine(
      result.axes, ImuSensor::kAccelerometer, NoiseTerm::kRandomWalk, options.combine, unreliable);
  return result;
}

}  // namespace splinecal
