#pragma once
#include <array>
#include <cstdint>
#include <optional>

#include "protocol/gs232_angles.hpp"
#include "protocol/line_assembler.hpp"
#include "protocol/session.hpp"

namespace rotord::protocol {

/// The Yaesu GS-232A / GS-232B computer interface (docs/protocols/gs232.md).
/// Commands end in CR (LF and CR LF work too) and are not echoed. Commands
/// without data answer a bare CR (gs232.ack_writes), data replies end in CR LF,
/// errors answer
/// `?>` CR LF. The variant (gs232.variant) is read for every command, so a
/// change on the web page takes effect at once.
class Gs232Session final : public Session {
 public:
  /// Points of the timed list (long-form M / W). The real controller holds
  /// 3800; 64 keep a session under 1 KB of RAM on the Pico, which is about a
  /// full satellite pass at one point every 15 s.
  static constexpr std::size_t kMaxListPoints = 64;
  /// "Wsss" and " aaa eee" per point, with room for extra spaces.
  static constexpr std::size_t kMaxLineLength = 16 + kMaxListPoints * 10;
  static constexpr std::string_view kError = "?>\r\n";
  static constexpr std::string_view kTooManyConnections = kError;

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

  Controller& controller_;
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
