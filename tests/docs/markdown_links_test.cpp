// Every relative link of every Markdown file in the repository names a file
// that is in it, and a `#anchor` names a heading of that file (issue 25: the
// README cited a design file the repository does not have). Links to the web
// (http:, https:, mailto:) are not followed: the tests run offline. So does
// every path of the repository its prose cites, as code (`core/web/api.cpp`)
// or as a word: a file, a directory, a pair named by its stem
// (`core/storage/flash_slots`) or a file one of the how-to's example patches
// (docs/examples/*.patch) adds; nothing else is exempt.
//
// Anchors follow GitHub's rule for headings: lower case, punctuation
// dropped, spaces as hyphens, a repeated heading numbered -1, -2, ...
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace rotord {
namespace {

namespace fs = std::filesystem;

const fs::path kRoot = ROTORD_SOURCE_DIR;

/// Build trees, dependencies fetched by npm and git's own files are not the
/// repository's documents.
bool skipped_directory(const fs::path& dir) {
  const std::string name = dir.filename().string();
  return name == ".git" || name == "node_modules" || name.rfind("build", 0) == 0;
}

std::vector<fs::path> markdown_files() {
  std::vector<fs::path> files;
  for (auto it = fs::recursive_directory_iterator(kRoot); it != fs::recursive_directory_iterator();
       ++it) {
    if (it->is_directory() && skipped_directory(it->path())) {
      it.disable_recursion_pending();
      continue;
    }
    if (it->is_regular_file() && it->path().extension() == ".md") files.push_back(it->path());
  }
  return files;
}

/// The lines of a Markdown file outside fenced code blocks (blank inside
/// them), code spans kept.
std::vector<std::string> prose_lines(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  bool fenced = false;
  for (std::string line; std::getline(in, line);) {
    const std::size_t first = line.find_first_not_of(' ');
    if (first != std::string::npos &&
        (line.compare(first, 3, "```") == 0 || line.compare(first, 3, "~~~") == 0)) {
      fenced = !fenced;
      lines.emplace_back();
      continue;
    }
    lines.push_back(fenced ? std::string() : line);
  }
  return lines;
}

/// A line with its code spans blanked: `[a](b)` shown as code is no link.
std::string without_code(std::string line) {
  bool in_code = false;
  for (char& c : line) {
    if (c == '`') in_code = !in_code;
    if (in_code) c = ' ';
  }
  return line;
}

/// GitHub's anchor for a heading's text.
std::string slug(const std::string& heading) {
  std::string out;
  for (const char raw : heading) {
    const auto c = static_cast<unsigned char>(raw);
    if (std::isalnum(c) || c == '-' || c == '_' || c >= 0x80)
      out += static_cast<char>(std::tolower(c));
    else if (c == ' ')
      out += '-';
  }
  return out;
}

/// The anchors a file offers: its headings (code spans keep their text) and
/// explicit `<a name=...>` / `id=...` targets.
std::set<std::string> anchors_of(const fs::path& file) {
  std::set<std::string> anchors;
  std::map<std::string, int> seen;
  std::ifstream in(file);
  bool fenced = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("```", 0) == 0 || line.rfind("~~~", 0) == 0) fenced = !fenced;
    if (fenced) continue;
    if (line.rfind("#", 0) == 0) {
      const std::size_t text = line.find_first_not_of('#');
      if (text != std::string::npos && line[text] == ' ') {
        const std::string base = slug(line.substr(text + 1));
        const int n = seen[base]++;
        anchors.insert(n == 0 ? base : base + "-" + std::to_string(n));
      }
    }
    for (const char* attribute : {"name=\"", "id=\""}) {
      for (std::size_t at = line.find(attribute); at != std::string::npos;
           at = line.find(attribute, at + 1)) {
        const std::size_t open = at + std::string(attribute).size();
        const std::size_t close = line.find('"', open);
        if (close != std::string::npos) anchors.insert(line.substr(open, close - open));
      }
    }
  }
  return anchors;
}

/// The targets of the inline links `[text](target)` of one prose line.
std::vector<std::string> link_targets(const std::string& line) {
  std::vector<std::string> targets;
  for (std::size_t at = line.find("]("); at != std::string::npos; at = line.find("](", at + 2)) {
    const std::size_t open = at + 2;
    const std::size_t close = line.find(')', open);
    if (close == std::string::npos) break;
    std::string target = line.substr(open, close - open);
    if (target.rfind('<', 0) == 0) {
      target = target.substr(1, target.find('>') - 1);  // [text](<path with spaces>)
    } else if (const std::size_t space = target.find(' '); space != std::string::npos) {
      target.resize(space);  // [text](path "title")
    }
    targets.push_back(target);
  }
  return targets;
}

bool is_external(const std::string& target) {
  return target.find("://") != std::string::npos || target.rfind("mailto:", 0) == 0;
}

/// What is wrong with one link of `file`, or "" when nothing is.
std::string check_link(const fs::path& file, const std::string& target,
                       std::map<fs::path, std::set<std::string>>& anchor_cache) {
  if (target.empty()) return "an empty link";
  if (is_external(target)) return "";
  const std::size_t hash = target.find('#');
  const std::string path = target.substr(0, hash);
  const std::string anchor = hash == std::string::npos ? "" : target.substr(hash + 1);
  const fs::path resolved = path.empty()          ? file
                            : path.front() == '/' ? kRoot / path.substr(1)
                                                  : file.parent_path() / path;
  if (!fs::exists(resolved)) return "names '" + path + "', which is not in the repository";
  if (anchor.empty() || resolved.extension() != ".md") return "";
  const fs::path key = fs::weakly_canonical(resolved);
  if (!anchor_cache.count(key)) anchor_cache[key] = anchors_of(key);
  if (!anchor_cache[key].count(anchor))
    return "names '#" + anchor + "', which is no heading of " +
           fs::relative(key, kRoot).generic_string();
  return "";
}

// ---- Paths the prose cites ----

/// The repository's top directories: a code span or a word of prose that
/// starts with one of them and a slash cites a path of the repository.
constexpr std::array<std::string_view, 10> kTopDirectories = {
    "core", "docs", "tests", "ports", "sim", "web", "bench", "scripts", "cmake", "debian"};

bool path_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '/' ||
         c == '-' || c == '+';
}

/// `word` as a cited path ("" when it is none): a top directory, a slash,
/// path characters (and, in code, `{hpp,cpp}` alternatives); a trailing
/// `:line`, `/` or full stop dropped. Globs are patterns, not citations.
std::string as_cited_path(std::string word) {
  if (const std::size_t colon = word.find(':'); colon != std::string::npos) word.resize(colon);
  while (!word.empty() && (word.back() == '.' || word.back() == '/')) word.pop_back();
  const std::size_t slash = word.find('/');
  if (slash == std::string::npos) return "";
  const std::string_view top(word.data(), slash);
  if (std::find(kTopDirectories.begin(), kTopDirectories.end(), top) == kTopDirectories.end())
    return "";
  const bool plain = std::all_of(word.begin(), word.end(), [](char c) {
    return path_char(c) || c == '{' || c == '}' || c == ',';
  });
  return plain ? word : "";
}

/// The repository paths one prose line cites: its code spans that are a
/// path, and its words that are one (outside code and link targets).
std::vector<std::string> cited_paths(const std::string& line) {
  std::vector<std::string> paths;
  std::string prose;
  for (std::size_t at = 0; at < line.size(); ++at) {
    const std::size_t close = line[at] == '`' ? line.find('`', at + 1) : std::string::npos;
    if (close == std::string::npos) {
      prose += line[at];
      continue;
    }
    if (std::string p = as_cited_path(line.substr(at + 1, close - at - 1)); !p.empty())
      paths.push_back(p);
    prose += ' ';
    at = close;
  }
  for (std::size_t at = prose.find("]("); at != std::string::npos; at = prose.find("](", at)) {
    const std::size_t close = prose.find(')', at);
    if (close == std::string::npos) break;
    prose.replace(at + 1, close - at, close - at, ' ');  // check_link's
  }
  for (std::size_t at = 0; at < prose.size();) {
    std::size_t end = at;
    while (end < prose.size() && path_char(prose[end])) ++end;
    const bool word_start = at == 0 || !(std::isalnum(static_cast<unsigned char>(prose[at - 1])) ||
                                         prose[at - 1] == '_');
    if (end > at && word_start) {
      if (std::string p = as_cited_path(prose.substr(at, end - at)); !p.empty()) paths.push_back(p);
    }
    at = end == at ? at + 1 : end;
  }
  return paths;
}

/// The files the how-to's example patches add (docs/examples/*.patch): a
/// page may cite them as the patch's.
std::set<std::string> files_the_examples_add() {
  std::set<std::string> files;
  const fs::path dir = kRoot / "docs" / "examples";
  if (!fs::is_directory(dir)) return files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".patch") continue;
    std::ifstream in(entry.path());
    std::string previous;
    for (std::string line; std::getline(in, line); previous = line) {
      if (previous == "--- /dev/null" && line.rfind("+++ b/", 0) == 0) files.insert(line.substr(6));
    }
  }
  return files;
}

/// What is wrong with one cited path, or "" when nothing is: each of its
/// `{a,b}` alternatives is a file or directory, a stem of files, or a file
/// an example patch adds.
std::string check_path(const fs::path& root, const std::string& path,
                       const std::set<std::string>& example_files) {
  std::vector<std::string> alternatives = {path};
  if (const std::size_t open = path.find('{'); open != std::string::npos) {
    const std::size_t close = path.find('}', open);
    if (close == std::string::npos) return "names '" + path + "', an unclosed {";
    alternatives.clear();
    std::stringstream choices(path.substr(open + 1, close - open - 1));
    for (std::string choice; std::getline(choices, choice, ',');)
      alternatives.push_back(path.substr(0, open) + choice + path.substr(close + 1));
  }
  for (const std::string& p : alternatives) {
    const bool stem = fs::exists(root / (p + ".hpp")) || fs::exists(root / (p + ".cpp"));
    if (!fs::exists(root / p) && !stem && !example_files.count(p))
      return "names '" + p + "', which is not in the repository";
  }
  return "";
}

TEST(MarkdownLinks, EveryPathTheProseCitesIsInTheRepository) {
  const std::set<std::string> example_files = files_the_examples_add();
  std::size_t paths = 0;
  for (const fs::path& file : markdown_files()) {
    const std::vector<std::string> lines = prose_lines(file);
    for (std::size_t i = 0; i < lines.size(); ++i) {
      for (const std::string& path : cited_paths(lines[i])) {
        ++paths;
        const std::string problem = check_path(kRoot, path, example_files);
        EXPECT_EQ(problem, "") << fs::relative(file, kRoot).generic_string() << ":" << i + 1 << ": "
                               << problem;
      }
    }
  }
  std::printf("checked %zu cited paths (%zu files of example patches among them)\n", paths,
              example_files.size());
  EXPECT_GE(paths, 200u);
}

TEST(MarkdownLinks, RefusesACitedPathThatIsNotInTheRepository) {
  EXPECT_EQ(
      cited_paths("see `core/web/web_api.cpp` and tests/unit/x_test.cpp:12, "
                  "[docs/a.md](docs/a.md), not `docs/protocols/*.md` or `make test`"),
      (std::vector<std::string>{"core/web/web_api.cpp", "tests/unit/x_test.cpp", "docs/a.md"}));
  EXPECT_EQ(cited_paths("`core/protocol/wrc_session.{hpp,cpp}`; ports/linux/."),
            (std::vector<std::string>{"core/protocol/wrc_session.{hpp,cpp}", "ports/linux"}));
  EXPECT_EQ(cited_paths("a/core/x.hpp, score/x.hpp, /etc/rotord/x"), std::vector<std::string>{});
  const std::set<std::string> examples = {"core/protocol/example_session.hpp"};
  EXPECT_EQ(check_path(kRoot, "core/web/web_api.cpp", examples), "");
  EXPECT_EQ(check_path(kRoot, "core/protocol/wrc_session.{hpp,cpp}", examples), "");
  EXPECT_EQ(check_path(kRoot, "core/storage/flash_slots", examples), "");
  EXPECT_EQ(check_path(kRoot, "core/protocol", examples), "");
  EXPECT_EQ(check_path(kRoot, "core/protocol/example_session.hpp", examples), "");
  EXPECT_NE(check_path(kRoot, "core/protocol/example_session.hpp", {}), "");
  EXPECT_NE(check_path(kRoot, "core/protocol/wrc_session.{hpp,txt}", examples), "");
  EXPECT_NE(check_path(kRoot, "PLAN.md", examples), "");
  EXPECT_NE(check_path(kRoot, "docs/plan.md", examples), "");
}

TEST(MarkdownLinks, EveryRelativeLinkNamesAFileAndHeadingOfTheRepository) {
  const std::vector<fs::path> files = markdown_files();
  ASSERT_GE(files.size(), 10u) << "no Markdown files found under " << kRoot;
  std::map<fs::path, std::set<std::string>> anchor_cache;
  std::size_t links = 0;
  for (const fs::path& file : files) {
    const std::vector<std::string> lines = prose_lines(file);
    for (std::size_t i = 0; i < lines.size(); ++i) {
      for (const std::string& target : link_targets(without_code(lines[i]))) {
        ++links;
        const std::string problem = check_link(file, target, anchor_cache);
        EXPECT_EQ(problem, "") << fs::relative(file, kRoot).generic_string() << ":" << i + 1
                               << ": link (" << target << ") " << problem;
      }
    }
  }
  std::printf("checked %zu links in %zu Markdown files\n", links, files.size());
}

// The checker on files it makes, so a checker that found nothing wrong with
// anything cannot pass unnoticed.
TEST(MarkdownLinks, RefusesAMissingFileAndAMissingHeading) {
  const fs::path dir = fs::temp_directory_path() / "rotord_markdown_links_test";
  fs::create_directories(dir / "sub");
  std::ofstream(dir / "sub" / "page.md")
      << "# A page\n\n## Limits (a flood)\n\n## Limits (a flood)\n";
  const fs::path readme = dir / "README.md";
  std::ofstream(readme) << "# Top\n";
  std::map<fs::path, std::set<std::string>> cache;
  EXPECT_EQ(check_link(readme, "sub/page.md", cache), "");
  EXPECT_EQ(check_link(readme, "sub/page.md#limits-a-flood", cache), "");
  EXPECT_EQ(check_link(readme, "sub/page.md#limits-a-flood-1", cache), "");
  EXPECT_EQ(check_link(readme, "#top", cache), "");
  EXPECT_EQ(check_link(readme, "https://example.org/nowhere.md", cache), "");
  EXPECT_NE(check_link(readme, "NO_SUCH_FILE.md", cache), "");
  EXPECT_NE(check_link(readme, "sub/page.md#limits", cache), "");
  EXPECT_NE(check_link(readme, "#nowhere", cache), "");
  EXPECT_EQ(link_targets("see [a](x.md), [b](<y z.md>) and [c](w.md \"title\")"),
            (std::vector<std::string>{"x.md", "y z.md", "w.md"}));
  EXPECT_EQ(slug("The firmware on an emulated RP2040 (`make hil`)"),
            "the-firmware-on-an-emulated-rp2040-make-hil");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rotord
