// docs/architecture.md draws the core's layer graph; core/layers.cmake is
// the graph the build uses and enforces. A layer or an edge added, removed or
// renamed in one and not the other fails here, naming it, so the drawing a
// newcomer reads cannot drift from the rules the build applies (issue 25:
// the README's old graph had).
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>

namespace rotord {
namespace {

/// Layer -> the layers it builds on directly.
using Graph = std::map<std::string, std::set<std::string>>;

std::string read_file(const std::string& relative) {
  std::ifstream in(std::string(ROTORD_SOURCE_DIR) + "/" + relative);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::set<std::string> words(const std::string& text) {
  std::set<std::string> out;
  std::istringstream in(text);
  for (std::string w; in >> w;) {
    if (w == "\"\"") continue;  // set(ROTORD_LAYER_util "")
    out.insert(w);
  }
  return out;
}

/// The graph of core/layers.cmake: ROTORD_LAYERS names the layers,
/// ROTORD_LAYER_<name> lists what each builds on. Comments are dropped first.
Graph graph_of_cmake(const std::string& text) {
  const std::string code = std::regex_replace(text, std::regex("#[^\n]*"), "");
  Graph graph;
  const std::regex layers(R"(set\(ROTORD_LAYERS\s([^)]*)\))");
  std::smatch m;
  if (std::regex_search(code, m, layers))
    for (const std::string& layer : words(m[1].str())) graph[layer];
  const std::regex deps(R"(set\(ROTORD_LAYER_([A-Za-z0-9_]+)([^)]*)\))");
  for (auto it = std::sregex_iterator(code.begin(), code.end(), deps); it != std::sregex_iterator();
       ++it)
    graph[(*it)[1].str()] = words((*it)[2].str());
  return graph;
}

/// The graph drawn in the first code block after `heading`: one line per
/// layer, `name -> dep, dep` or a bare `name` for a layer on nothing.
Graph graph_of_doc(const std::string& doc, const std::string& heading) {
  Graph graph;
  std::istringstream lines(doc);
  std::string line;
  bool in_section = false, in_block = false;
  while (std::getline(lines, line)) {
    if (!in_section) {
      in_section = line == heading;
      continue;
    }
    if (line.rfind("```", 0) == 0) {
      if (in_block) break;
      in_block = true;
      continue;
    }
    if (!in_block) continue;
    const std::size_t arrow = line.find("->");
    std::string deps = arrow == std::string::npos ? "" : line.substr(arrow + 2);
    for (char& c : deps)
      if (c == ',') c = ' ';
    const std::set<std::string> name = words(line.substr(0, arrow));
    if (name.size() != 1) {
      ADD_FAILURE() << "not a layer line in the graph: '" << line << "'";
      continue;
    }
    graph[*name.begin()] = words(deps);
  }
  return graph;
}

std::string join(const std::set<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "(nothing)" : out;
}

TEST(ArchitectureDoc, LayerGraphIsTheOneTheBuildEnforces) {
  const Graph built = graph_of_cmake(read_file("core/layers.cmake"));
  const Graph drawn = graph_of_doc(read_file("docs/architecture.md"), "### The layer graph");
  ASSERT_GE(built.size(), 10u) << "core/layers.cmake: no layers read";
  ASSERT_FALSE(drawn.empty()) << "docs/architecture.md: no graph under '### The layer graph'";
  for (const auto& [layer, deps] : built) {
    const auto it = drawn.find(layer);
    if (it == drawn.end()) {
      ADD_FAILURE() << "layer '" << layer << "' (core/layers.cmake) is not drawn in "
                    << "docs/architecture.md";
      continue;
    }
    EXPECT_EQ(it->second, deps) << "layer '" << layer << "' builds on " << join(deps)
                                << " in core/layers.cmake, but on " << join(it->second)
                                << " in docs/architecture.md";
  }
  for (const auto& [layer, deps] : drawn)
    EXPECT_TRUE(built.count(layer)) << "docs/architecture.md draws layer '" << layer
                                    << "', which core/layers.cmake does not have";
}

// The parser itself, on a graph small enough to check by eye: a test that
// read nothing from both files would otherwise pass.
TEST(ArchitectureDoc, ReadsBothNotations) {
  const Graph cmake = graph_of_cmake(
      "# a comment with set(ROTORD_LAYER_x y)\n"
      "set(ROTORD_LAYERS\n    util hal web)\n"
      "set(ROTORD_LAYER_util \"\")\nset(ROTORD_LAYER_hal util)\n"
      "set(ROTORD_LAYER_web hal util)\n");
  const Graph doc = graph_of_doc(
      "## other\n```\nx -> y\n```\n### The layer graph\n\ntext\n```\n"
      "web -> hal, util\nhal -> util\nutil\n```\nafter -> the block\n",
      "### The layer graph");
  const Graph expected = {{"util", {}}, {"hal", {"util"}}, {"web", {"hal", "util"}}};
  EXPECT_EQ(cmake, expected);
  EXPECT_EQ(doc, expected);
}

}  // namespace
}  // namespace rotord
