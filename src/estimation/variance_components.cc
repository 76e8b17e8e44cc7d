#include "splinecal/estimation/variance_components.h"

#include <algorithm>
#include <map>

#include "compressed_information.h"

namespace splinecal {

VarianceComponents EstimateVarianceComponents(ceres::Problem* problem,
                                              const ResidualGroupOf& group_of,
                                              const VarianceComponentOptions& options,
                                              const std::map<int, double>& group_ranks) {
  VarianceComponents result;
  const internal::CompressedInformation information(
      problem, group_of, {}, options.num_threads);
  if (information.evaluation_failed()) return result;
  std::map<int, double> traces;
  if (!information.LabelTraces(&traces)) return result;
  result.ok = true;
  for (const auto& [label, rows] : information.num_residuals()) {
    VarianceComponent& group = result.groups[label];
    group.num_residuals = rows;
    group.squared_sum = information.squared_sum().at(label);
    const auto rank = group_ranks.find(label);
    const double independent = rank == group_ranks.end() ? rows : rank->second;
    group.redundancy = std::clamp(independent - traces[label], 0.0, independent);
    group.identifiable = group.redundancy >= options.min_redundancy;
    if (group.identifiable) group.factor = group.squared_sum / group.redundancy;
  }
  return result;
}

}  // namespace splinecal
