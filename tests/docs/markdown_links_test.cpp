// Every relative link of every Markdown file in the repository names a file
// that is in it, and a `#anchor` names a heading of that file (issue 25: the
// README cited a design file the repository does not have). Links to the web
// (http:, https:, mailto:) are not followed: the tests run offline.
//
// Anchors follow GitHub's rule for headings: lower case, punctuation
// dropped, spaces as hyphens, a repeated heading numbered -1, -2, ...
#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
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

/// The lines of a Markdown file outside fenced code blocks, with inline code
/// spans blanked: a path shown as code is an example, not a link.
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
    if (fenced) {
      lines.emplace_back();
      continue;
    }
    bool in_code = false;
    for (char& c : line) {
      if (c == '`') in_code = !in_code;
      if (in_code) c = ' ';
    }
    lines.push_back(line);
  }
  return lines;
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

TEST(MarkdownLinks, EveryRelativeLinkNamesAFileAndHeadingOfTheRepository) {
  const std::vector<fs::path> files = markdown_files();
  ASSERT_GE(files.size(), 10u) << "no Markdown files found under " << kRoot;
  std::map<fs::path, std::set<std::string>> anchor_cache;
  std::size_t links = 0;
  for (const fs::path& file : files) {
    const std::vector<std::string> lines = prose_lines(file);
    for (std::size_t i = 0; i < lines.size(); ++i) {
      for (const std::string& target : link_targets(lines[i])) {
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
