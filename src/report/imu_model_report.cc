#include "splinecal/report/imu_model_report.h"

#include <cmath>
#include <string>
#include <vector>

#include "splinecal/lie/so3.h"
#include "splinecal/string_printf.h"
#include "splinecal/units.h"

namespace splinecal {

namespace {

struct Entry {
  double value;
  double std;      // NaN: none
  bool parameter;  // false: fixed by the model's form (M's upper triangle)
};

struct Row {
  std::string name;  // with its unit
  const char* format;
  std::vector<Entry> entries;
};

// M (lower triangular) or A (full), row by row; `scale` converts to the shown unit.
void AddMatrixRows(const std::string& name,
                   const char* format,
                   const Eigen::Matrix3d& value,
                   const Eigen::Matrix3d& std,
                   bool lower_triangular,
                   std::vector<Row>* rows) {
  for (int r = 0; r < 3; ++r) {
    Row row{name + " row " + std::to_string(r), format, {}};
    for (int c = 0; c < 3; ++c) {
      row.entries.push_back({value(r, c), std(r, c), !lower_triangular || c <= r});
    }
    rows->push_back(row);
  }
}

Row VectorRow(const std::string& name, const char* format, const Eigen::Vector3d& value,
              const Eigen::Vector3d& std) {
  Row row{name, format, {}};
  for (int k = 0; k < 3; ++k) row.entries.push_back({value[k], std[k], true});
  return row;
}

std::vector<Row> ImuModelRows(const ImuCalibration& imu, const ImuModelStd& s) {
  const ImuIntrinsicsd& p = imu.intrinsics;
  std::vector<Row> rows;
  AddMatrixRows("M_a", "%.6f", p.M_a, s.M_a, true, &rows);
  AddMatrixRows("M_g", "%.6f", p.M_g, s.M_g, true, &rows);
  AddMatrixRows("A [(rad/s)/(m/s^2)]", "%.3e", p.A, s.A, false, &rows);
  // C_gyro_i = Exp(phi): its std is phi's per axis (calibrate.h, ImuModelStd).
  rows.push_back(VectorRow("C_gyro_i rotation vector [deg]",
                           "%.4f",
                           SO3d(Eigen::Quaterniond(p.C_gyro_i)).Log() * kRadToDeg,
                           s.C_gyro_i_deg));
  if (imu.model == ImuModelKind::kScaleMisalignmentSizeEffect) {
    rows.push_back(VectorRow("ry_i [mm]", "%.3f", 1e3 * p.ry_i, 1e3 * s.ry_i));
    rows.push_back(VectorRow("rz_i [mm]", "%.3f", 1e3 * p.rz_i, 1e3 * s.rz_i));
  }
  return rows;
}

// A parameter's std, or why it has none: calibrate holds the parameters a recording does not
// determine at nominal and reports no std for them (a warning names them); without a covariance
// no parameter has one.
std::string StdOf(const Row& row, const Entry& e, bool covariance_ok) {
  if (!e.parameter) return "-";
  if (std::isfinite(e.std)) return StringPrintf(row.format, e.std);
  return covariance_ok ? "held" : "no std";
}

std::string ValueOf(const Row& row, const Entry& e) {
  return e.parameter ? StringPrintf(row.format, e.value) : StringPrintf("%g", e.value);
}

// One IMU's model and its label (imu0 the reference, imuN (name) a further one).
struct ImuModelOf {
  const ImuCalibration* imu;
  const ImuModelStd* std;
  std::string label;
};

// Calls f for every IMU whose model is not `calibrated`, the reference first.
template <typename F>
void ForEachModel(const CalibrationResult& r, const F& f) {
  if (r.imu_model.model != ImuModelKind::kCalibrated) f(ImuModelOf{&r.imu_model, &r.imu_model_std, "imu0"});
  for (size_t i = 0; i < r.further_imus.size(); ++i) {
    const FurtherImuEstimate& e = r.further_imus[i];
    if (e.calibration.model == ImuModelKind::kCalibrated) continue;
    f(ImuModelOf{&e.calibration, &e.model_std, "imu" + std::to_string(i + 1) + " (" + e.name + ")"});
  }
}

}  // namespace

std::string ImuModelText(const CalibrationResult& result) {
  std::string text;
  ForEachModel(result, [&](const ImuModelOf& m) {
    text += std::string("IMU model ") + ImuModelName(m.imu->model) + " (Kalibr's " + m.label +
            "; each entry: value (std))\n";
    for (const Row& row : ImuModelRows(*m.imu, *m.std)) {
      text += "  " + row.name + ":";
      for (size_t k = 0; k < row.entries.size(); ++k) {
        const Entry& e = row.entries[k];
        text += (k == 0 ? " " : ", ") + ValueOf(row, e);
        if (e.parameter) text += " (" + StdOf(row, e, result.covariance_ok) + ")";
      }
      text += "\n";
    }
  });
  return text;
}

std::string ImuModelHtml(const CalibrationResult& result) {
  std::string html;
  ForEachModel(result, [&](const ImuModelOf& m) {
    html += std::string("<h2>IMU model</h2>\n<p>Kalibr's ") + ImuModelName(m.imu->model) +
            " model of " + m.label +
            " (docs/imu_models.md); \"held\": not determined by the recording, kept at "
            "nominal.</p>\n<table>\n";
    for (const Row& row : ImuModelRows(*m.imu, *m.std)) {
      std::string values, stds;
      for (size_t k = 0; k < row.entries.size(); ++k) {
        values += (k == 0 ? "" : ", ") + ValueOf(row, row.entries[k]);
        stds += (k == 0 ? "" : ", ") + StdOf(row, row.entries[k], result.covariance_ok);
      }
      html +=
          "<tr><th>" + row.name + "</th><td>" + values + "</td><td>std " + stds + "</td></tr>\n";
    }
    html += "</table>\n";
  });
  return html;
}

}  // namespace splinecal
