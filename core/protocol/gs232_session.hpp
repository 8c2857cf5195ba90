#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "protocol/gs232_angles.hpp"
#include "protocol/line_assembler.hpp"
#include "protocol/line_reply.hpp"
#include "protocol/session.hpp"
#include "rotator/client_frame.hpp"

namespace rotord::protocol {

/// The Yaesu GS-232A / GS-232B computer interface (docs/protocols/gs232.md).
/// Commands end in CR (LF and CR LF work too) and are not echoed. Commands
/// without data answer a bare CR (gs232.ack_writes), data replies end in CR LF,
/// errors answer
/// `?>` CR LF. The variant (gs232.variant) is read for every command, so a
/// change on the web page takes effect at once.
class Gs232Session final : public Session {
 public:
  std::string_view front() const override { return "gs232"; }
  /// Points of the timed list (long-form M / W). The real controller holds
  /// 3800; 64 keep a session under 1 KB of RAM on the Pico, which is about a
  /// full satellite pass at one point every 15 s.
  static constexpr std::size_t kMaxListPoints = 64;
  /// "Wsss" and " aaa eee" per point, with room for extra spaces.
  static constexpr std::size_t kMaxLineLength = 16 + kMaxListPoints * 10;
  static constexpr std::string_view kError = "?>\r\n";
  static constexpr std::string_view kTooManyConnections = kError;
  /// Data replies end in CR LF; one that cannot fit is the error prompt.
  static constexpr ReplyRules kReplyRules{"\r\n", kError};
  static constexpr std::size_t kMaxReplyLength = 64;
  using Reply = LineReply<kMaxReplyLength>;

  /// What may follow a command's letter (spaces inside are ignored, and at
  /// most three characters are; `M` and `W` take the rest of the line).
  enum class Arg : std::uint8_t {
    kNone,   ///< `C`
    kExact,  ///< exactly Command::arg_text: `C2`, `P36`
    kSpeed,  ///< one digit 1..4: `X1`..`X4`
    kList,   ///< `M` / `W`: numbers to the end of the line (position_command)
  };
  /// One row of the command table (gs232_session.cpp). The help pages
  /// (`H`, `H2`, `H3`) are generated from these rows at compile time, and
  /// docs/protocols/gs232.md is checked against them (tests/docs).
  struct Command {
    std::string_view name;  ///< as the help page prints it: `C2`, `Maaa`, `X1-X4`
    char letter;            ///< upper case; matched case-insensitively
    Arg arg;
    std::string_view arg_text;  ///< for kExact
    bool b_only;                ///< the GS-232A answers `?>`
    /// nullptr: another row of the same letter runs it (the long forms of
    /// `M` and `W` share the short form's handler); the row gives help.
    void (Gs232Session::*run)(std::string_view arg, ByteSink& out);
    std::string_view help;
    std::uint8_t help_pages;  ///< bit n-1: listed on page n (`H`, `H2`, `H3`)
    /// Turns, sets the speed, runs a list, calibrates or changes the scale:
    /// `?>` to a read-only client (Session::may_control). `S`, `A` and `E`
    /// (stop) are not.
    bool changes_state;
  };
  static const Command kCommands[];
  static std::span<const Command> commands();
  /// The help page `H`, `H2` or `H3` (without H3's mode lines); empty for others.
  static std::string_view help_page(int page);

  explicit Gs232Session(Controller& controller) : controller_(controller) {}

  void receive(std::string_view bytes, ByteSink& out) override;
  /// Steps the timed list.
  void poll(Millis now, ByteSink& out) override;

  /// Handles one command (no line end); public for tests and fuzzing.
  void handle_line(std::string_view line, ByteSink& out);

  /// The timed list, for tests.
  std::size_t list_size() const { return list_size_; }
  bool list_running() const { return running_; }

 private:
  enum class Pending : std::uint8_t { kNone, kAzOffset, kElOffset };
  struct Point {
    std::int16_t az_deg;
    std::int16_t el_deg;  ///< -1 in an azimuth-only (M) list
  };

  /// The end of a command without data: a bare CR (gs232.ack_writes).
  void done(ByteSink& out);
  /// done() when `e` is kOk, else the error prompt.
  void reply(Error e, ByteSink& out);
  bool is_b() const;
  gs232::AzRange range() const;
  void position_command(bool with_el, std::string_view args, ByteSink& out);
  Error go(int az_deg, std::optional<int> el_deg);
  Error go_to_point(std::size_t index);
  void stop_list() { running_ = false; }
  /// C (azimuth), B (elevation) or 2 (C2: both) in the variant's format.
  void report(char what, ByteSink& out);
  void write_position(char what, int az_deg, int el_deg, ByteSink& out);
  void calibration(AxisId axis, bool full_scale, ByteSink& out);
  void confirm(std::string_view answer, ByteSink& out);
  void help(int page, ByteSink& out);

  // The handlers of the command table.
  void report_az(std::string_view arg, ByteSink& out);
  void report_el(std::string_view arg, ByteSink& out);
  void report_both(std::string_view arg, ByteSink& out);
  void turn_cw(std::string_view arg, ByteSink& out);
  void turn_ccw(std::string_view arg, ByteSink& out);
  void turn_up(std::string_view arg, ByteSink& out);
  void turn_down(std::string_view arg, ByteSink& out);
  void stop_az(std::string_view arg, ByteSink& out);
  void stop_el(std::string_view arg, ByteSink& out);
  void stop_all(std::string_view arg, ByteSink& out);
  void speed(std::string_view arg, ByteSink& out);
  void go_az(std::string_view arg, ByteSink& out);
  void go_az_el(std::string_view arg, ByteSink& out);
  void start_list(std::string_view arg, ByteSink& out);
  void list_point(std::string_view arg, ByteSink& out);
  void offset_az(std::string_view arg, ByteSink& out);
  void offset_el(std::string_view arg, ByteSink& out);
  void full_scale_az(std::string_view arg, ByteSink& out);
  void full_scale_el(std::string_view arg, ByteSink& out);
  void help_1(std::string_view arg, ByteSink& out);
  void help_2(std::string_view arg, ByteSink& out);
  void help_3(std::string_view arg, ByteSink& out);
  void scale_360(std::string_view arg, ByteSink& out);
  void scale_450(std::string_view arg, ByteSink& out);
  void south_centre(std::string_view arg, ByteSink& out);
  /// R, L, U, D: end a running list, then turn.
  void turn(AxisId axis, Direction dir, ByteSink& out);
  /// A, E: end a running list, stop one axis.
  void stop_axis(AxisId axis, ByteSink& out);

  Controller& controller_;
  ClientFrame frame_;  // the azimuth frame this client sends in
  LineAssembler<kMaxLineLength> lines_;
  std::array<Point, kMaxListPoints> list_{};
  std::uint16_t list_size_ = 0;
  std::uint16_t list_index_ = 0;  ///< the point turned to last
  bool running_ = false;
  Millis step_ms_ = 0;
  Millis next_step_at_ = 0;
  Pending pending_ = Pending::kNone;
  /// Z: where the client says the indicator needle starts. rotord knows the
  /// end stops from the travel settings, so this is only reported (H3).
  bool south_centre_ = false;
};

}  // namespace rotord::protocol
