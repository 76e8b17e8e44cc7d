// The names of the options that the commands and the Python module read and result.yaml writes
// back, one table per option for both directions (enum_names.h): fit's --bias-model and allan's
// --combine.
#ifndef SPLINECAL_REPORT_OPTION_NAMES_H_
#define SPLINECAL_REPORT_OPTION_NAMES_H_

#include <array>

#include "splinecal/allan/allan.h"
#include "splinecal/enum_names.h"
#include "splinecal/estimation/bias_costs.h"

namespace splinecal {

// The bias models (estimation/bias_costs.h), the default first.
inline constexpr std::array<EnumName<BiasModel>, 2> kBiasModelNames = {{
    {BiasModel::kConstant, "constant"},
    {BiasModel::kSpline, "spline"},
}};

// How the Kalibr keys combine the identified axes (allan/allan.h), the default first.
inline constexpr std::array<EnumName<CombineAxes>, 2> kCombineAxesNames = {{
    {CombineAxes::kMean, "mean"},
    {CombineAxes::kMax, "max"},
}};

}  // namespace splinecal

#endif  // SPLINECAL_REPORT_OPTION_NAMES_H_
