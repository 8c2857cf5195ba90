// Each doc lists exactly its table's commands (issue 11): the command tables
// in the code are the one list; a row added, renamed or removed without its
// doc fails here, naming what is missing on which side. Docs are checked
// rather than generated so they keep their prose, examples and per-command
// notes; only the list of names must agree.
#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "protocol/console_session.hpp"
#include "protocol/easycomm_session.hpp"
#include "protocol/gs232_session.hpp"
#include "protocol/n1mm_rotor.hpp"
#include "protocol/pst_rotor.hpp"
#include "protocol/rotctld_commands.hpp"
#include "protocol/seed_session.hpp"
#include "protocol/wrc_session.hpp"
#include "settings/rotator_models.hpp"
#include "web/web_api.hpp"

namespace rotord {
namespace {

using Names = std::set<std::string>;

std::string read_doc(const std::string& relative) {
  std::ifstream in(std::string(ROTORD_SOURCE_DIR) + "/" + relative);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The cells of one column of the first Markdown table after the line
/// `heading`, header and separator rows left out. `\|` inside a cell is no
/// column break.
std::vector<std::string> column(const std::string& doc, const std::string& heading,
                                std::size_t index) {
  std::vector<std::string> cells;
  std::istringstream lines(doc);
  std::string line;
  bool in_section = false;
  int table_row = 0;
  while (std::getline(lines, line)) {
    if (!in_section) {
      in_section = line == heading;
      continue;
    }
    if (line.rfind("|", 0) != 0) {
      if (table_row > 0) break;  // the table ended
      continue;
    }
    if (++table_row <= 2) continue;  // header, separator
    std::vector<std::string> row;
    std::string cell;
    for (std::size_t i = 1; i < line.size(); ++i) {
      if (line[i] == '\\' && i + 1 < line.size() && line[i + 1] == '|') {
        cell += '|';
        ++i;
      } else if (line[i] == '|') {
        row.push_back(cell);
        cell.clear();
      } else {
        cell += line[i];
      }
    }
    if (index < row.size()) cells.push_back(row[index]);
  }
  return cells;
}

/// The `code` spans of a cell.
std::vector<std::string> codes(const std::string& cell) {
  std::vector<std::string> out;
  std::size_t at = 0;
  for (;;) {
    const std::size_t open = cell.find('`', at);
    if (open == std::string::npos) break;
    const std::size_t close = cell.find('`', open + 1);
    if (close == std::string::npos) break;
    out.push_back(cell.substr(open + 1, close - open - 1));
    at = close + 1;
  }
  return out;
}

std::vector<std::string> words(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

template <typename Table>
Names names_of(const Table& table) {
  Names names;
  for (const auto& row : table) names.insert(std::string(row.name));
  return names;
}

TEST(CommandDocs, WrcPageListsExactlyTheWrcCommands) {
  Names documented;
  for (const std::string& cell : column(read_doc("docs/protocols/wrc.md"), "## Commands", 0))
    for (const std::string& code : codes(cell)) documented.insert(words(code).at(0));
  EXPECT_EQ(documented, names_of(protocol::WrcSession::commands()));
}

TEST(CommandDocs, RotctldPageListsExactlyTheRotctldCommands) {
  const std::string doc = read_doc("docs/protocols/rotctld.md");
  Names long_names, codes_documented;
  for (const std::string& cell : column(doc, "## Commands", 1))
    for (const std::string& code : codes(cell))
      for (const std::string& w : words(code)) long_names.insert(w);
  for (const std::string& cell : column(doc, "## Commands", 0))
    for (const std::string& code : codes(cell))
      for (const std::string& w : words(code)) codes_documented.insert(w);
  Names table_names, table_codes;
  for (const protocol::rotctld::Command& c : protocol::rotctld::commands()) {
    table_names.insert(c.name);
    // Hamlib's internal codes (0x8f, ...) have no letter to document.
    if (c.code < 0x80) table_codes.insert(std::string(1, static_cast<char>(c.code)));
  }
  EXPECT_EQ(long_names, table_names);
  EXPECT_EQ(codes_documented, table_codes);
}

TEST(CommandDocs, Gs232PageListsExactlyTheGs232Commands) {
  Names documented;
  for (const std::string& cell : column(read_doc("docs/protocols/gs232.md"), "## Commands", 0))
    for (const std::string& code : codes(cell)) documented.insert(code);
  EXPECT_EQ(documented, names_of(protocol::Gs232Session::commands()));
}

TEST(CommandDocs, UdpPageListsExactlyTheN1mmElementsAndPstCommands) {
  const std::string doc = read_doc("docs/protocols/udp.md");
  Names elements, commands;
  for (const std::string& cell : column(doc, "## N1MM+ elements", 0))
    for (const std::string& code : codes(cell)) elements.insert(code);
  for (const std::string& cell : column(doc, "## PstRotator commands", 0))
    for (const std::string& code : codes(cell)) commands.insert(code);
  EXPECT_EQ(elements, names_of(protocol::N1mmRotor::elements()));
  EXPECT_EQ(commands, names_of(protocol::PstRotor::commands()));
}

TEST(CommandDocs, EasycommPageListsExactlyTheEasycommCommands) {
  // "AZx.x", "CW r,value", "STtime": the command is the upper-case letters
  // it starts with.
  Names documented;
  for (const std::string& cell : column(read_doc("docs/protocols/easycomm.md"), "## Commands", 0))
    for (const std::string& code : codes(cell))
      for (const std::string& w : words(code)) {
        std::string name;
        for (char c : w) {
          if (!std::isupper(static_cast<unsigned char>(c))) break;
          name += c;
        }
        if (name.size() >= 2) documented.insert(name);
      }
  EXPECT_EQ(documented, names_of(protocol::EasycommSession::commands()));
}

TEST(CommandDocs, SeedPageListsExactlyTheSeedCommands) {
  Names documented;  // "$S,n" -> S
  for (const std::string& cell : column(read_doc("docs/protocols/seed.md"), "## Commands", 0))
    for (const std::string& code : codes(cell))
      if (code.size() >= 2 && code[0] == '$') documented.insert(code.substr(1, 1));
  EXPECT_EQ(documented, names_of(protocol::SeedSession::commands()));
}

TEST(CommandDocs, ConsolePageListsExactlyTheConsoleCommands) {
  Names documented;  // "`get <key>`" -> get
  for (const std::string& cell : column(read_doc("docs/protocols/console.md"), "## Commands", 0))
    for (const std::string& code : codes(cell))
      if (!words(code).empty()) documented.insert(words(code).front());
  EXPECT_EQ(documented, names_of(protocol::ConsoleSession::commands()));
}

TEST(CommandDocs, WebApiEndpointTableIsTheRouteTable) {
  const std::string doc = read_doc("docs/web_api.md");
  const std::vector<std::string> endpoints = column(doc, "## Endpoints", 0);
  const std::vector<std::string> who = column(doc, "## Endpoints", 1);
  const std::vector<std::string> lock = column(doc, "## Endpoints", 2);
  const std::vector<std::string> what = column(doc, "## Endpoints", 3);
  const auto routes = web::Api::routes();
  ASSERT_EQ(endpoints.size(), routes.size());
  for (std::size_t n = 0; n < routes.size(); ++n) {
    const web::Api::Route& r = routes[n];
    static constexpr const char* kWho[] = {"anyone", "a login or any token",
                                           "a login or a control token", "the web login"};
    const std::string path(r.path);
    // A state-changing row is POST, or the methods it names (PUT DELETE).
    std::vector<std::string> expected;
    if (!r.post) {
      expected.push_back("GET " + path);
    } else if (r.verbs.empty()) {
      expected.push_back("POST " + path);
    } else {
      std::string verbs(r.verbs);
      for (std::size_t at = 0; at < verbs.size();) {
        const std::size_t space = verbs.find(' ', at);
        expected.push_back(verbs.substr(at, space - at) + " " + path);
        at = space == std::string::npos ? verbs.size() : space + 1;
      }
    }
    EXPECT_EQ(codes(endpoints[n]), expected);
    EXPECT_EQ(words(who[n]), words(kWho[static_cast<int>(r.need)])) << path;
    EXPECT_EQ(words(lock[n]),
              r.locked ? std::vector<std::string>{"refused"} : std::vector<std::string>{})
        << path;
    EXPECT_EQ(words(what[n]), words(std::string(r.help))) << path;
  }
}

TEST(CommandDocs, RotatorModelsPageListsExactlyTheModelRows) {
  Names documented;  // "`hygain-ham4`" -> hygain-ham4
  for (const std::string& cell : column(read_doc("docs/rotator_models.md"), "## The list", 0))
    for (const std::string& code : codes(cell)) documented.insert(code);
  Names rows;
  for (const settings::RotatorModel& m : settings::rotator_models()) rows.insert(m.id);
  EXPECT_EQ(documented, rows);
}

}  // namespace
}  // namespace rotord
