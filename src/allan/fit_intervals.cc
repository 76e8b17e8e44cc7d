// FitIntervals (allan/noise_fit.h): the relative intervals of a curve's points, per noise type.
#include <glog/logging.h>

#include "splinecal/allan/noise_fit.h"
#include "splinecal/error.h"
#include "splinecal/string_printf.h"

namespace splinecal {

FitIntervals::FitIntervals(int64_t num_samples,
                           const std::vector<int64_t>& cluster_sizes,
                           const std::vector<int64_t>& strides,
                           const NoiseFitOptions& options)
    : num_samples_(num_samples), cluster_sizes_(cluster_sizes), strides_(strides) {
  CHECK(strides.empty() || strides.size() == cluster_sizes.size());
  for (const double confidence : {options.confidence, options.bound_confidence}) {
    if (!(confidence > 0.0 && confidence < 1.0)) {
      throw Error(StringPrintf("confidence must be in (0, 1), got %g", confidence));
    }
  }
  for (const bool bound : {false, true}) {
    const double confidence = bound ? options.bound_confidence : options.confidence;
    for (int j = 0; j < kNumNoiseTerms; ++j) {
      const PowerLawNoise noise = NoiseTermNoiseType(static_cast<NoiseTerm>(j));
      std::vector<DeviationInterval>& table = relative_[bound][static_cast<int>(noise)];
      if (!table.empty()) continue;  // the random walk and the rate ramp share random-walk FM
      for (size_t i = 0; i < cluster_sizes.size(); ++i) {
        const int64_t stride = strides.empty() ? 1 : strides[i];
        const double edf = StridedAllanEdf(noise, num_samples, cluster_sizes[i], stride);
        table.push_back(AllanDeviationInterval(1.0, edf, confidence));
      }
    }
  }
}

bool FitIntervals::Fits(const AllanCurve& curve) const {
  const bool strides_match =
      curve.strides == strides_ ||
      (curve.strides.empty() && strides_ == std::vector<int64_t>(cluster_sizes_.size(), 1)) ||
      (strides_.empty() && curve.strides == std::vector<int64_t>(cluster_sizes_.size(), 1));
  return curve.num_samples == num_samples_ && curve.cluster_sizes == cluster_sizes_ &&
         strides_match;
}

const DeviationInterval& FitIntervals::Relative(NoiseTerm term, bool bound, size_t i) const {
  return relative_[bound][static_cast<int>(NoiseTermNoiseType(term))].at(i);
}

}  // namespace splinecal
