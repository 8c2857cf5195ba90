#include "protocol/gs232_session.hpp"

#include <array>
#include <cstdio>

#include "protocol/gs232_detail.hpp"
#include "rotator/controller.hpp"
#include "util/slice.hpp"
#include "util/text.hpp"

namespace rotord::protocol {

using gs232::detail::upper;
using settings::Id;

// The command table. Its order is the help pages' order: a row is listed on
// every page its help_pages bit names (T, N and S on both pages 1 and 2).
using A = Gs232Session::Arg;
constexpr Gs232Session::Command Gs232Session::kCommands[] = {
    {"R", 'R', A::kNone, {}, false, &Gs232Session::turn_cw, "turn clockwise", 1, true},
    {"L", 'L', A::kNone, {}, false, &Gs232Session::turn_ccw, "turn counter-clockwise", 1, true},
    {"A", 'A', A::kNone, {}, false, &Gs232Session::stop_az, "stop azimuth", 1, false},
    {"C", 'C', A::kNone, {}, false, &Gs232Session::report_az, "report azimuth", 1, false},
    {"Maaa", 'M', A::kList, {}, false, &Gs232Session::go_az, "turn to azimuth aaa", 1, true},
    {"Msss aaa aaa ...",
     'M',
     A::kList,
     {},
     false,
     nullptr,
     "timed list, sss seconds per step",
     1,
     true},
    {"U", 'U', A::kNone, {}, false, &Gs232Session::turn_up, "turn up", 2, true},
    {"D", 'D', A::kNone, {}, false, &Gs232Session::turn_down, "turn down", 2, true},
    {"E", 'E', A::kNone, {}, false, &Gs232Session::stop_el, "stop elevation", 2, false},
    {"B", 'B', A::kNone, {}, false, &Gs232Session::report_el, "report elevation", 2, false},
    {"C2", 'C', A::kExact, "2", false, &Gs232Session::report_both, "report azimuth and elevation",
     2, false},
    {"Waaa eee",
     'W',
     A::kList,
     {},
     false,
     &Gs232Session::go_az_el,
     "turn to azimuth aaa, elevation eee",
     2,
     true},
    {"Wsss aaa eee ...", 'W', A::kList, {}, false, nullptr, "timed list of pairs", 2, true},
    {"T", 'T', A::kNone, {}, false, &Gs232Session::start_list, "start the timed list", 1 | 2, true},
    {"N",
     'N',
     A::kNone,
     {},
     false,
     &Gs232Session::list_point,
     "timed list: point now and points stored",
     1 | 2,
     false},
    {"X1-X4",
     'X',
     A::kSpeed,
     {},
     false,
     &Gs232Session::speed,
     "azimuth speed, 1 slowest to 4 fastest",
     1,
     true},
    {"S", 'S', A::kNone, {}, false, &Gs232Session::stop_all, "stop everything", 1 | 2, false},
    {"O",
     'O',
     A::kNone,
     {},
     false,
     &Gs232Session::offset_az,
     "offset calibration at the CCW stop",
     1,
     true},
    {"F",
     'F',
     A::kNone,
     {},
     false,
     &Gs232Session::full_scale_az,
     "full scale calibration at the CW stop",
     1,
     true},
    {"O2", 'O', A::kExact, "2", false, &Gs232Session::offset_el,
     "elevation offset calibration at the bottom", 2, true},
    {"F2", 'F', A::kExact, "2", false, &Gs232Session::full_scale_el,
     "elevation full scale calibration at the top", 2, true},
    {"H", 'H', A::kNone, {}, false, &Gs232Session::help_1, "help page 1", 0, false},
    {"H2", 'H', A::kExact, "2", false, &Gs232Session::help_2, "help page 2", 0, false},
    {"H3", 'H', A::kExact, "3", true, &Gs232Session::help_3, "help page 3 and the mode", 0, false},
    {"P36", 'P', A::kExact, "36", true, &Gs232Session::scale_360, "360 degree azimuth scale", 4,
     true},
    {"P45", 'P', A::kExact, "45", true, &Gs232Session::scale_450, "450 degree azimuth scale", 4,
     true},
    // Z only changes what H3 reports (this session's needle), nothing else.
    {"Z",
     'Z',
     A::kNone,
     {},
     true,
     &Gs232Session::south_centre,
     "toggle north / south centred needle",
     4,
     false},
};

std::span<const Gs232Session::Command> Gs232Session::commands() {
  return kCommands;
}

namespace {

// The help pages, built at compile time from the rows: a header, then
// "name   help" lines with the name padded to seven columns (two spaces
// after a longer one), as the manual's help screen prints them.
constexpr std::string_view kPageHeader = "---------- COMMAND LIST 0 ----------\r\n";
constexpr std::size_t kHeaderDigit = 24;

constexpr std::size_t name_column(const Gs232Session::Command& c) {
  return c.name.size() < 7 ? 7 : c.name.size() + 2;
}

constexpr std::size_t page_length(int page) {
  std::size_t n = kPageHeader.size();
  for (const Gs232Session::Command& c : Gs232Session::kCommands)
    if ((c.help_pages & (1 << (page - 1))) != 0) n += name_column(c) + c.help.size() + 2;
  return n;
}

template <int Page>
constexpr std::array<char, page_length(Page)> make_page() {
  std::array<char, page_length(Page)> text{};
  std::size_t n = 0;
  for (char ch : kPageHeader) text[n++] = ch;
  text[kHeaderDigit] = static_cast<char>('0' + Page);
  for (const Gs232Session::Command& c : Gs232Session::kCommands) {
    if ((c.help_pages & (1 << (Page - 1))) == 0) continue;
    const std::size_t end = n + name_column(c);
    for (char ch : c.name) text[n++] = ch;
    while (n < end) text[n++] = ' ';
    for (char ch : c.help) text[n++] = ch;
    text[n++] = '\r';
    text[n++] = '\n';
  }
  return text;
}

constexpr auto kPage1 = make_page<1>();
constexpr auto kPage2 = make_page<2>();
constexpr auto kPage3 = make_page<3>();

}  // namespace

std::string_view Gs232Session::help_page(int page) {
  switch (page) {
    case 1:
      return {kPage1.data(), kPage1.size()};
    case 2:
      return {kPage2.data(), kPage2.size()};
    case 3:
      return {kPage3.data(), kPage3.size()};
    default:
      return {};
  }
}

void Gs232Session::done(ByteSink& out) {
  // The real controllers send a CR after every command. Hamlib's GS-232A/B
  // backends never read it (they flush the input before the next command, 50
  // ms later); the generic ones (602, 607, 608) write the next command at once
  // and can take it for the position reply, hence gs232.ack_writes.
  if (controller_.settings().b(Id::kGs232AckWrites)) out.write("\r");
}

void Gs232Session::reply(Error e, ByteSink& out) {
  if (e != Error::kOk) return out.write(kError);
  done(out);
}

bool Gs232Session::is_b() const {
  return controller_.settings().i(Id::kGs232Variant) == 1;
}

gs232::AzRange Gs232Session::range() const {
  return gs232::az_range(controller_.settings(), controller_.limits());
}

void Gs232Session::receive(std::string_view bytes, ByteSink& out) {
  lines_.feed(bytes, [&](std::string_view line, bool overflowed) {
    if (overflowed) {
      // Too long even for a full timed list: like any bad M / W, the stored
      // list is gone and nothing moves.
      pending_ = Pending::kNone;
      list_size_ = 0;
      stop_list();
      out.write(kError);
      return;
    }
    handle_line(line, out);
  });
}

void Gs232Session::poll(Millis /*now*/, ByteSink& /*out*/) {
  // The controller's clock, not the transport's: the list runs in the same
  // (possibly simulated) time as the motion it commands.
  if (!running_ || controller_.now() < next_step_at_) return;
  if (list_index_ + 1u >= list_size_) {
    running_ = false;  // the last point was reached; N keeps reporting it
    return;
  }
  ++list_index_;
  next_step_at_ += step_ms_;
  if (go_to_point(list_index_) != Error::kOk) running_ = false;
}

void Gs232Session::handle_line(std::string_view line, ByteSink& out) {
  line = text::trim(line);
  if (pending_ != Pending::kNone) {
    if (line.empty()) return;  // the Enter after "are you sure?" is not an answer yet
    return confirm(line, out);
  }
  // Hamlib's GS-232B backend sends an extra CR after every command without a
  // reply; empty commands are ignored so that nothing answers it.
  if (line.empty()) return;
  const char letter = upper(line[0]);
  const std::string_view rest = text::slice(line, 1);
  for (const Command& c : kCommands) {
    if (c.letter != letter) continue;
    if (!command_arrives(letter == 'S' || letter == 'A' || letter == 'E')) return;
    break;
  }
  // A read-only client (access.control_networks, the control lock) is
  // refused every letter that can change something, before its argument is
  // looked at: M, W, R, L, U, D, X, T, O, F and P. S, A and E (stop) work.
  for (const Command& c : kCommands) {
    if (c.letter == letter && c.changes_state &&
        !may_control(controller_, std::string_view(&c.letter, 1)))
      return out.write(kError);
  }
  // Every command but M and W is a letter and at most three characters;
  // spaces inside are ignored ("C 2" as the manual's help screen prints it).
  char arg_buf[3];
  std::size_t n = 0;
  bool too_long = false;
  for (char c : rest) {
    if (c == ' ' || c == '\t') continue;
    if (n == sizeof(arg_buf)) {
      too_long = true;
      break;
    }
    arg_buf[n++] = upper(c);
  }
  const std::string_view arg(arg_buf, n);
  for (const Command& c : kCommands) {
    if (c.letter != letter || c.run == nullptr) continue;
    if (c.arg == Arg::kList) return (this->*c.run)(rest, out);
    if (too_long) break;
    const bool matches = c.arg == Arg::kNone    ? arg.empty()
                         : c.arg == Arg::kExact ? arg == c.arg_text
                                                : arg.size() == 1 && arg[0] >= '1' && arg[0] <= '4';
    if (!matches || (c.b_only && !is_b())) continue;
    return (this->*c.run)(arg, out);
  }
  out.write(kError);
}

}  // namespace rotord::protocol
