// Overlapping Allan deviation of a uniformly sampled rate signal (one gyro or accelerometer axis).
//
// With samples y_0 .. y_{N-1} at rate f (tau_0 = 1 / f), the integrated signal (angle or velocity)
// is theta_k = tau_0 * sum_{i<k} y_i, k = 0 .. N. For a cluster of m samples (averaging time
// tau = m tau_0) the overlapping Allan variance is [IEEE952, annex C], [Riley08, "overlapping
// Allan variance"]
//
//     AVAR(tau) = 1 / (2 tau^2 (N - 2m + 1)) * sum_{k=0}^{N-2m} (theta_{k+2m} - 2 theta_{k+m} +
//     theta_k)^2
//
// i.e. half the mean squared difference of the averages of adjacent clusters, taken at every
// start sample. The deviation ADEV = sqrt(AVAR) is in the unit of y (rad/s, m/s^2).
//
// Cost: theta is built once (O(N)); each averaging time is then one pass over theta, O(N), for
// any m. theta is accumulated in long double after removing the mean of y (a constant adds
// nothing to the second difference, and removing it keeps |theta| small), then stored as double:
// 8 bytes per sample (theta_0 = 0 is implicit, so N doubles hold theta_1 .. theta_N).
//
// Error bar: the relative 1-sigma uncertainty of ADEV estimated from K = floor(N / m)
// independent clusters is 1 / sqrt(2 (K - 1)) [IEEE952, annex C], [ElSheimy08]; it is
// conservative for the overlapping estimator, which uses more (correlated) differences.
//
// Under a work budget (allan/work_budget.h) an averaging time may use only every s-th start index
// k = 0, s, 2s, ...: the same second differences, T = floor((N - 2m) / s) + 1 of them,
//
//     AVAR_s(tau) = 1 / (2 tau^2 T) * sum_{k = 0, s, 2s, ... <= N - 2m} d_k^2,
//     d_k = theta_{k+2m} - 2 theta_{k+m} + theta_k,
//
// an unbiased estimate of the same Allan variance; its error bar uses K = min(N / m, T).
//
// References: [IEEE952] IEEE Std 952-1997, IEEE Standard Specification Format Guide and Test
// Procedure for Single-Axis Interferometric Fiber Optic Gyros, annex C; [Riley08] W. J. Riley,
// "Handbook of Frequency Stability Analysis", NIST SP 1065, 2008; [ElSheimy08] N. El-Sheimy,
// H. Hou, X. Niu, "Analysis and Modeling of Inertial Sensors Using Allan Variance", IEEE Trans.
// Instrum. Meas. 57(1), 2008.
#ifndef SPLINECAL_ALLAN_ALLAN_DEVIATION_H_
#define SPLINECAL_ALLAN_ALLAN_DEVIATION_H_

#include <cstdint>
#include <string>
#include <vector>

namespace splinecal {

// One Allan deviation curve, one entry per averaging time (increasing).
struct AllanCurve {
  double rate_hz = 0.0;                // sample rate f [Hz]
  int64_t num_samples = 0;             // N
  std::vector<int64_t> cluster_sizes;  // m
  std::vector<double> tau_s;           // tau = m / f [s]
  std::vector<double> adev;            // overlapping Allan deviation [unit of y]
  std::vector<double> adev_error;      // 1-sigma error of adev [unit of y]
  // Every strides[i]-th start index was used, num_terms[i] of them (allan/work_budget.h; stride 1:
  // the overlapping estimator, num_terms = N - 2m + 1). Empty in a curve built by hand: stride 1.
  std::vector<int64_t> strides;
  std::vector<int64_t> num_terms;
};

// Log-spaced cluster sizes m = round(10^(j / taus_per_decade)), j = 0, 1, ..., de-duplicated, up
// to max_tau_fraction * num_samples (and never above num_samples / 2, so K >= 2). Throws
// splinecal::Error when taus_per_decade is not in [1, 1000] or max_tau_fraction not in (0, 0.5].
// May return an empty list when num_samples is too small.
std::vector<int64_t> AllanClusterSizes(int64_t num_samples,
                                       int taus_per_decade,
                                       double max_tau_fraction);

// The integrated, mean-removed signal theta of a sample series (see the file comment), built in
// place so that a series of N samples needs N doubles in total. The unit of theta is that of
// y times seconds.
class IntegratedSignal {
 public:
  // Consumes `samples` (their storage becomes theta). Throws splinecal::Error naming `name`
  // ("gyro x") and the sample index when a sample is not finite, when rate_hz is not positive and
  // finite, when there are fewer than 2 samples, or when all samples are equal (a constant
  // signal has no noise to identify).
  IntegratedSignal(std::vector<double>&& samples, double rate_hz, const std::string& name);

  int64_t num_samples() const { return static_cast<int64_t>(sums_.size()); }
  double rate_hz() const { return rate_hz_; }
  double mean() const { return mean_; }  // of the samples [unit of y]

  // Overlapping Allan variance [unit of y squared] for a cluster of m samples, 1 <= m <= N / 2.
  // One O(N) pass.
  double AllanVariance(int64_t m) const;

  // The curve at the given cluster sizes (each in [1, N / 2]), on up to num_threads threads
  // (the passes are split into tasks whose sums are combined in a fixed order: the result does
  // not depend on num_threads).
  AllanCurve Deviation(const std::vector<int64_t>& cluster_sizes, int num_threads = 1) const;

  // The curve with averaging time i taken at every strides[i]-th start index (see the file
  // comment; allan/work_budget.h chooses them). All strides 1: the same bits as the overload
  // above. Otherwise every stride must divide the largest (powers of two do); the strided sums
  // read a window of a polyphase copy of the integrated signal (2 max(m) * 1.5 doubles: 24 MB at
  // N = 10^7), kept in *scratch when given so that the next call reuses it (fresh memory is slow
  // to write the first time on virtual machines: 4 ms per MB on this project's).
  AllanCurve Deviation(const std::vector<int64_t>& cluster_sizes,
                       const std::vector<int64_t>& strides,
                       int num_threads = 1,
                       std::vector<double>* scratch = nullptr) const;

 private:
  void CheckClusterSize(int64_t m) const;
  std::vector<double> Variances(const std::vector<int64_t>& cluster_sizes, int num_threads) const;
  // AVAR(m) from sum_{k>=1} of the squared second differences (adds the k = 0 term).
  double Normalise(int64_t m, long double sum_of_k_at_least_1) const;

  // sums_[k - 1] = theta_k / tau_0 = sum_{i<k} (y_i - mean), k = 1 .. N [unit of y]; theta_0 = 0.
  std::vector<double> sums_;
  double rate_hz_;
  double mean_;
};

// Convenience: the overlapping Allan deviation of `samples` at `cluster_sizes` (copies the
// samples; see IntegratedSignal for the errors thrown).
AllanCurve OverlappingAllanDeviation(const std::vector<double>& samples,
                                     double rate_hz,
                                     const std::vector<int64_t>& cluster_sizes,
                                     const std::string& name = "signal");

// Relative 1-sigma error of an Allan deviation from num_samples / m independent clusters:
// 1 / sqrt(2 (K - 1)) [ElSheimy08]. Requires 2 <= K.
double AllanRelativeError(int64_t num_samples, int64_t m);

// The same for every stride-th start index: K = min(num_samples / m, terms) (stride 1: the value
// above). Infinite below K = 2.
double AllanRelativeError(int64_t num_samples, int64_t m, int64_t stride);

}  // namespace splinecal

#endif  // SPLINECAL_ALLAN_ALLAN_DEVIATION_H_
