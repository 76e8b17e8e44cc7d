// The source tree's architecture as a test: every area of include/splinecal/ and src/ includes
// only areas of lower layers, so no two areas include each other (directly or around a longer
// circle). The layers are the ones include/splinecal/splinecal.h lists; a new area goes into
// kLayers at the place its includes allow, and an include that points upwards fails here with
// the file and line that adds it. The installed API is the public headers: the umbrella includes
// each of them, and none includes an internal one (include/splinecal/<area>/detail/, cli/), which
// the install leaves out (CMakeLists.txt).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "testing/paths.h"

namespace splinecal {
namespace {

namespace fs = std::filesystem;

// Bottom to top. "" is the root of include/splinecal/ (error.h, units.h, string_printf.h).
const std::vector<std::string> kLayers = {
    "",             // the one error type, units, string formatting
    "lie",          // SO(3), SE(3), manifolds
    "spline",       // the SE(3) spline and its knot layout
    "imu",          // IMU data types, measurement model, dead reckoning
    "camera",       // camera models, camchains, targets, observations, PnP
    "io",           // readers and writers of every file format (plain data in, out)
    "plot",         // SVG plots (no knowledge of what is plotted)
    "detect",       // target corners in images (the image front end, OpenCV and libapriltag)
    "estimation",   // residuals, the spline problem, covariance, solver rounds
    "vio",          // preintegration, hand-eye, alignment, clock correlation
    "sim",          // IMU and camera simulation, trajectories
    "allan",        // Allan deviation and noise identification
    "calib",        // fit and calibrate
    "intrinsics",   // camera intrinsics and camera-to-camera extrinsics from target views
    "report",       // result files and HTML reports of fit and calibrate
    "cli",          // the command-line front end
};

struct IncludeEdge {
  std::string file;  // relative to the source tree
  int line = 0;
  std::string from_area;
  std::string to_area;
  std::string included;  // the included header below include/splinecal/ ("io/detail/x.h")
};

// A header of the library's internals, not installed: <area>/detail/*.h (shared by src/ and the
// tests) and the command line's cli/*.h.
bool IsInternalHeader(const std::string& relative) {
  return relative.find("/detail/") != std::string::npos || relative.rfind("cli/", 0) == 0;
}

// The area of a path below include/splinecal/ or src/: its first folder ("" for the root).
std::string AreaOf(const fs::path& relative) {
  return relative.has_parent_path() ? relative.begin()->string() : std::string();
}

std::vector<IncludeEdge> CollectIncludes(const fs::path& source_dir) {
  static const std::regex kInclude(
      R"re(^\s*#\s*include\s+"splinecal/((?:([a-z_]+)/)?(?:detail/)?[^"/]+)")re");
  std::vector<IncludeEdge> edges;
  for (const fs::path& root : {source_dir / "include" / "splinecal", source_dir / "src"}) {
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
      if (!entry.is_regular_file()) continue;
      const std::string ext = entry.path().extension().string();
      if (ext != ".h" && ext != ".cc") continue;
      // The umbrella header includes every area by design (it is above all of them).
      if (entry.path() == source_dir / "include" / "splinecal" / "splinecal.h") continue;
      const std::string from_area = AreaOf(fs::relative(entry.path(), root));
      std::ifstream in(entry.path());
      std::string text;
      int line = 0;
      while (std::getline(in, text)) {
        ++line;
        std::smatch match;
        if (!std::regex_search(text, match, kInclude)) continue;
        edges.push_back({fs::relative(entry.path(), source_dir).string(), line, from_area,
                         match[2].matched ? match[2].str() : std::string(), match[1].str()});
      }
    }
  }
  return edges;
}

int LayerOf(const std::string& area) {
  for (size_t i = 0; i < kLayers.size(); ++i) {
    if (kLayers[i] == area) return static_cast<int>(i);
  }
  return -1;
}

TEST(Layering, SourceTreeHasIncludes) {
  // Guards the test itself: a wrong path or regex would find nothing and pass vacuously.
  const std::vector<IncludeEdge> edges = CollectIncludes(testing::SourceDir());
  EXPECT_GT(edges.size(), 300u);
  std::set<std::string> areas;
  for (const IncludeEdge& e : edges) areas.insert(e.from_area);
  EXPECT_GE(areas.size(), kLayers.size() - 1);
}

TEST(Layering, EveryAreaIsALayer) {
  for (const IncludeEdge& e : CollectIncludes(testing::SourceDir())) {
    EXPECT_GE(LayerOf(e.from_area), 0) << e.file << ": area '" << e.from_area
                                       << "' is not in kLayers: place it there";
    EXPECT_GE(LayerOf(e.to_area), 0) << e.file << ":" << e.line << ": includes area '"
                                     << e.to_area << "', which is not in kLayers";
  }
}

TEST(Layering, AreasIncludeOnlyLowerLayers) {
  for (const IncludeEdge& e : CollectIncludes(testing::SourceDir())) {
    if (e.from_area == e.to_area) continue;
    EXPECT_LT(LayerOf(e.to_area), LayerOf(e.from_area))
        << e.file << ":" << e.line << ": area '" << e.from_area << "' includes '" << e.to_area
        << "', a layer above it (tests/architecture/layering_test.cc lists the order)";
  }
}

// The umbrella header is the public API a user reads: every public header is in it, area by area
// in layer order, and no internal one (detail/; cli/ is the front end, not the library).
TEST(Layering, UmbrellaHeaderIncludesEveryLibraryHeaderInLayerOrder) {
  const fs::path include_dir = fs::path(testing::SourceDir()) / "include" / "splinecal";
  std::ifstream umbrella(include_dir / "splinecal.h");
  ASSERT_TRUE(umbrella.good());
  static const std::regex kInclude(
      R"re(^#include "splinecal/(([a-z_]+)/)?((?:detail/)?[a-z_0-9]+\.h)")re");
  std::set<std::string> listed;
  int previous_layer = 0;
  std::string text;
  while (std::getline(umbrella, text)) {
    std::smatch match;
    if (!std::regex_search(text, match, kInclude)) continue;
    const std::string area = match[2].matched ? match[2].str() : std::string();
    listed.insert(match[1].str() + match[3].str());
    EXPECT_FALSE(IsInternalHeader(match[1].str() + match[3].str()))
        << text << ": an internal header in the public API";
    EXPECT_GE(LayerOf(area), previous_layer) << text << " comes after a higher layer";
    previous_layer = std::max(previous_layer, LayerOf(area));
  }
  for (const auto& entry : fs::recursive_directory_iterator(include_dir)) {
    if (!entry.is_regular_file() || entry.path().extension() != ".h") continue;
    const std::string relative = fs::relative(entry.path(), include_dir).string();
    if (relative == "splinecal.h" || IsInternalHeader(relative)) continue;
    EXPECT_EQ(listed.count(relative), 1u) << relative << " is missing from splinecal.h";
  }
}

// The install copies the public headers only, so a public header that includes an internal one
// would not compile in an installed tree (tests/consumer builds programs against one).
TEST(Layering, PublicHeadersIncludeNoInternalHeader) {
  int public_includes = 0;
  for (const IncludeEdge& e : CollectIncludes(testing::SourceDir())) {
    const std::string prefix = "include/splinecal/";
    if (e.file.rfind(prefix, 0) != 0 || IsInternalHeader(e.file.substr(prefix.size()))) continue;
    ++public_includes;
    EXPECT_FALSE(IsInternalHeader(e.included))
        << e.file << ":" << e.line << ": a public header includes the internal "
        << e.included << " (move it to detail/, or the included header out of it)";
  }
  EXPECT_GT(public_includes, 200);  // the test reads the tree, not nothing
}

TEST(Layering, InternalHeadersAreTold) {
  EXPECT_TRUE(IsInternalHeader("io/detail/number_parser_avx2.h"));
  EXPECT_TRUE(IsInternalHeader("cli/common_flags.h"));
  EXPECT_FALSE(IsInternalHeader("io/number_parser.h"));
  EXPECT_FALSE(IsInternalHeader("splinecal.h"));
}

using AreaGraph = std::map<std::string, std::set<std::string>>;

// One circle of areas that include each other, first area repeated at the end ("a -> b -> a"),
// or an empty list when the graph has none (depth-first search with an explicit path).
std::vector<std::string> FindCycle(const AreaGraph& graph) {
  std::map<std::string, int> state;  // absent: unvisited, 1: on the path, 2: done
  std::vector<std::string> path;
  std::vector<std::string> cycle;
  std::function<bool(const std::string&)> visit = [&](const std::string& area) {
    state[area] = 1;
    path.push_back(area);
    const auto edges = graph.find(area);
    if (edges != graph.end()) {
      for (const std::string& next : edges->second) {
        if (state[next] == 1) {
          cycle.assign(std::find(path.begin(), path.end(), next), path.end());
          cycle.push_back(next);
          return true;
        }
        if (state[next] == 0 && visit(next)) return true;
      }
    }
    path.pop_back();
    state[area] = 2;
    return false;
  };
  for (const auto& entry : graph) {
    if (state[entry.first] == 0 && visit(entry.first)) break;
  }
  return cycle;
}

std::string Join(const std::vector<std::string>& areas) {
  std::string text;
  for (const std::string& area : areas) text += (text.empty() ? "" : " -> ") + area;
  return text;
}

TEST(Layering, FindCycleFindsACircleAndOnlyACircle) {
  EXPECT_THAT(FindCycle({{"io", {"imu"}}, {"allan", {"io", "imu"}}}), ::testing::IsEmpty());
  EXPECT_EQ(Join(FindCycle({{"io", {"allan"}}, {"allan", {"io"}}})), "allan -> io -> allan");
  EXPECT_EQ(Join(FindCycle({{"a", {"b"}}, {"b", {"c"}}, {"c", {"a"}}, {"d", {"a"}}})),
            "a -> b -> c -> a");
}

// The property as the architecture states it, independent of kLayers' order: the area graph of
// the real tree has no cycle. Reported as a circle of areas, so that a wrong kLayers order and a
// real cycle are told apart.
TEST(Layering, AreaGraphHasNoCycle) {
  AreaGraph graph;
  for (const IncludeEdge& e : CollectIncludes(testing::SourceDir())) {
    if (e.from_area != e.to_area) graph[e.from_area].insert(e.to_area);
  }
  const std::vector<std::string> cycle = FindCycle(graph);
  EXPECT_TRUE(cycle.empty()) << "areas include each other: " << Join(cycle);
}

}  // namespace
}  // namespace splinecal
