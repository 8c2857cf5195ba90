#pragma once
// The rotord console (docs/protocols/console.md): a small line protocol for
// a person or a script at a serial terminal, to configure, calibrate and
// reset a controller reached only over USB (a plain Pico, a Pico W without
// Wi-Fi), where no protocol of a rotator controller has a command for that
// (GS-232 cannot even clear a latched fault). The Pico serves it on its USB
// log port (CDC 0), Linux on `--pty console` (and TCP with --console-port).
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "command/system_commands.hpp"
#include "protocol/line_assembler.hpp"
#include "protocol/line_reply.hpp"
#include "protocol/session.hpp"
#include "settings/settings.hpp"

namespace rotord::protocol {

/// What a port gives its console sessions; every member may be missing, and
/// the commands that need it then answer so.
struct ConsolePort {
  /// The board's defaults, the base of `export` (settings_layers.hpp);
  /// nullptr: the table's.
  const settings::Settings* defaults = nullptr;
  /// A working copy for `import` (all or nothing) and for `export` without
  /// `defaults`: shared by every session of the port, used only inside one
  /// call. nullptr: import is refused.
  settings::Settings* scratch = nullptr;
  command::SystemHooks* system = nullptr;  ///< nullptr: reboot and bootsel refused
  const char* board = "";                  ///< shown by `status`, e.g. "Pico W"
};

/// One console session. Every command is answered by zero or more lines of
/// information, then exactly one last line: `ok`, `ok <detail>` or
/// `error: <reason>`, CR LF ended, so a script reads up to that line.
class ConsoleSession final : public Session {
 public:
  std::string_view front() const override { return "console"; }
  /// A command line; a longer one is refused whole (`import` documents
  /// longer than this are split into several imports, docs/protocols/console.md).
  static constexpr std::size_t kMaxLineLength = 512;
  /// Input that arrives while a long listing is still going out waits here;
  /// more than this is dropped and reported.
  static constexpr std::size_t kHoldBytes = 256;
  static constexpr std::size_t kMaxReplyLength = 256;
  static constexpr std::string_view kTooManyConnections =
      "error: busy: too many console clients\r\n";
  static constexpr ReplyRules kReplyRules{"\r\n", "error: reply too long\r\n"};
  using Reply = LineReply<kMaxReplyLength>;

  /// One row of the command table (console_session.cpp); docs/protocols/
  /// console.md lists exactly these (tests/docs).
  struct Command {
    std::string_view name;
    std::string_view usage;
    void (ConsoleSession::*run)(std::string_view args, ByteSink& out);
    std::string_view help;
    /// Refused to a client that may not control (Session::may_control):
    /// everything that moves, writes a setting or reboots. `stop` never is.
    bool changes_state;
  };
  static std::span<const Command> commands();

  ConsoleSession(Controller& controller, const char* version, const ConsolePort* port)
      : controller_(controller), version_(version), port_(port) {}

  void receive(std::string_view bytes, ByteSink& out) override;
  bool output_pending() const override { return listing_ != Listing::kNone; }
  void write_more(std::size_t room_bytes, ByteSink& out) override;

  /// Handles one command line (no line end); public for tests and fuzzing.
  void handle_line(std::string_view line, ByteSink& out);

 private:
  static const Command kCommands[];

  /// A reply longer than a transport takes at once, sent in windows of the
  /// bytes it has room for (write_more): rebuilt from the settings each time,
  /// so it costs no buffer.
  /// kHeld: the listing is out; what was typed during it is answered in
  /// the next window (not beyond the room the last one had).
  enum class Listing : std::uint8_t { kNone, kExport, kList, kHeld };

  void help(std::string_view args, ByteSink& out);
  void status(std::string_view args, ByteSink& out);
  void get(std::string_view args, ByteSink& out);
  void list(std::string_view args, ByteSink& out);
  void set(std::string_view args, ByteSink& out);
  void export_settings(std::string_view args, ByteSink& out);
  void import_settings(std::string_view args, ByteSink& out);
  void calibrate(std::string_view args, ByteSink& out);
  void setup(std::string_view args, ByteSink& out);       // console_setup.cpp
  void commission(std::string_view args, ByteSink& out);  // console_setup.cpp
  void stop(std::string_view args, ByteSink& out);
  void reset(std::string_view args, ByteSink& out);
  void reboot(std::string_view args, ByteSink& out);
  void bootsel(std::string_view args, ByteSink& out);
  // Where the beam points (console_places.cpp).
  void bearing(std::string_view args, ByteSink& out);
  void turn(std::string_view args, ByteSink& out);
  void presets(std::string_view args, ByteSink& out);
  void preset(std::string_view args, ByteSink& out);
  // The wear odometer (console_care.cpp).
  void odometer(std::string_view args, ByteSink& out);
  // The wind stow (console_care.cpp, docs/care.md).
  void wind(std::string_view args, ByteSink& out);

  void start_listing(Listing listing, std::string_view prefix, ByteSink& out);
  /// Writes the whole listing into `out` (which drops what lies outside the
  /// window it was asked for); returns its length.
  void write_listing(ByteSink& out) const;
  const settings::Settings* export_base() const;
  void feed(std::string_view bytes, ByteSink& out);

  Controller& controller_;
  const char* version_;
  const ConsolePort* port_;
  LineAssembler<kMaxLineLength> lines_;
  Listing listing_ = Listing::kNone;
  std::size_t listing_sent_ = 0;         ///< bytes of the listing already out
  std::uint32_t listing_revision_ = 0;   ///< the settings it began with
  char list_prefix_[48] = "";            ///< `list <prefix>`
  std::array<char, kHoldBytes> hold_{};  ///< input held while a listing goes out
  std::size_t held_ = 0;
  std::size_t hold_dropped_ = 0;
};

}  // namespace rotord::protocol
