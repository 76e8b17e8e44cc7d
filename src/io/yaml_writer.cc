#include "splinecal/io/yaml_writer.h"

#include <glog/logging.h>

#include <cmath>

#include "splinecal/string_printf.h"

namespace splinecal {

std::string YamlNumber(double value) {
  if (std::isnan(value)) return ".nan";
  if (std::isinf(value)) return value > 0 ? ".inf" : "-.inf";
  return FormatDouble(value);
}

std::string YamlString(const std::string& value) {
  std::string quoted = "\"";
  for (char c : value) {
    switch (c) {
      case '"': quoted += "\\\""; break;
      case '\\': quoted += "\\\\"; break;
      case '\n': quoted += "\\n"; break;
      case '\t': quoted += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          quoted += StringPrintf("\\x%02x", static_cast<unsigned char>(c));
        } else {
          quoted += c;
        }
    }
  }
  return quoted + "\"";
}

void YamlWriter::Key(const std::string& key) {
  if (item_pending_) {
    text_.append(2 * depth_ - 2, ' ');
    text_ += "- ";
    item_pending_ = false;
  } else {
    text_.append(2 * depth_, ' ');
  }
  text_ += key + ":";
}

void YamlWriter::BeginList(const std::string& key) {
  Key(key);
  text_ += "\n";
  ++depth_;
}

void YamlWriter::BeginListItem() {
  CHECK(!item_pending_) << "an empty list item";
  ++depth_;
  item_pending_ = true;
}

void YamlWriter::EndListItem() {
  CHECK(!item_pending_) << "an empty list item";
  CHECK_GT(depth_, 1);
  --depth_;
}

void YamlWriter::EndList() {
  CHECK_GT(depth_, 0);
  --depth_;
}

void YamlWriter::Comment(const std::string& text) {
  text_.append(2 * depth_, ' ');
  text_ += "# " + text + "\n";
}

void YamlWriter::Scalar(const std::string& key, double value) {
  Key(key);
  text_ += " " + YamlNumber(value) + "\n";
}

void YamlWriter::Scalar(const std::string& key, int64_t value) {
  Key(key);
  text_ += " " + std::to_string(value) + "\n";
}

void YamlWriter::Scalar(const std::string& key, bool value) {
  Key(key);
  text_ += value ? " true\n" : " false\n";
}

void YamlWriter::Scalar(const std::string& key, const std::string& value) {
  Key(key);
  text_ += " " + YamlString(value) + "\n";
}

void YamlWriter::Vector(const std::string& key, const Eigen::VectorXd& value) {
  Key(key);
  text_ += " [";
  for (Eigen::Index i = 0; i < value.size(); ++i) {
    text_ += (i == 0 ? "" : ", ") + YamlNumber(value[i]);
  }
  text_ += "]\n";
}

void YamlWriter::Matrix(const std::string& key, const Eigen::MatrixXd& value) {
  Key(key);
  text_ += "\n";
  for (Eigen::Index r = 0; r < value.rows(); ++r) {
    text_.append(2 * depth_ + 2, ' ');
    text_ += "- [";
    for (Eigen::Index c = 0; c < value.cols(); ++c) {
      text_ += (c == 0 ? "" : ", ") + YamlNumber(value(r, c));
    }
    text_ += "]\n";
  }
}

void YamlWriter::StringList(const std::string& key, const std::vector<std::string>& values) {
  Key(key);
  if (values.empty()) {
    text_ += " []\n";
    return;
  }
  text_ += "\n";
  for (const std::string& value : values) {
    text_.append(2 * depth_ + 2, ' ');
    text_ += "- " + YamlString(value) + "\n";
  }
}

void YamlWriter::BeginMap(const std::string& key) {
  Key(key);
  text_ += "\n";
  ++depth_;
}

void YamlWriter::EndMap() {
  CHECK_GT(depth_, 0) << "EndMap without BeginMap";
  --depth_;
}

std::string YamlWriter::str() const {
  CHECK_EQ(depth_, 0) << "unclosed map in YamlWriter";
  return text_;
}

}  // namespace splinecal
