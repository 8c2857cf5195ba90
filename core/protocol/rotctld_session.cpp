// The rotctld stream parser. It follows rotctl_parse() of Hamlib 4.5.4, which
// reads the socket with fscanf("%c") for the command and fscanf("%s") for each
// argument; see docs/protocols/rotctld.md for the rules and the deviations.
#include "protocol/rotctld_session.hpp"

#include "protocol/rotctld_number.hpp"
#include "rotator/controller.hpp"
#include "util/slice.hpp"

namespace rotord::protocol {

using rotctld::Command;
using rotctld::HamlibError;

namespace {

bool is_line_end(char c) {
  return c == '\r' || c == '\n';
}

/// scanf's white space: it ends an argument token.
bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' || c == '\r';
}

bool is_name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}

/// rotctld takes any ASCII punctuation before a command as the Extended
/// Response Protocol separator, except '\' (long names), '_' (get_info) and
/// '#' (comments). '?' works too, whatever the man page says.
bool is_separator(char c) {
  const bool punct = (c >= '!' && c <= '/') || (c >= ':' && c <= '@') || (c >= '[' && c <= '`') ||
                     (c >= '{' && c <= '~');
  return punct && c != '\\' && c != '_' && c != '#';
}

}  // namespace

void RotctldSession::receive(std::string_view bytes, ByteSink& out) {
  consume(bytes, out);
}

void RotctldSession::consume(std::string_view bytes, ByteSink& out) {
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    if (state_ == State::kClosed) return;
    if (paused_) {
      // rotctld sleeps in its connection thread and reads nothing meanwhile;
      // hold the input and run it when the pause ends. Beyond the buffer it
      // is dropped (a client that pauses and floods gets what fits).
      const std::string_view rest = text::slice(bytes, i);
      for (char c : rest) {
        if (pause_input_length_ < pause_input_.size()) pause_input_[pause_input_length_++] = c;
      }
      return;
    }
    feed(bytes[i], out);
  }
}

void RotctldSession::poll(Millis now, ByteSink& out) {
  if (!paused_) return;
  if (!pause_started_) {
    // The first poll after the command: the pause runs from here, so it lasts
    // at least its seconds (one transport poll longer at most).
    pause_started_ = true;
    pause_until_ = now + pause_ms_;
    return;
  }
  if (now < pause_until_) return;
  paused_ = false;
  out.write(reply_.view());  // the \pause reply, held until now as rotctld does
  std::array<char, kPauseInputBytes> held;
  const std::size_t n = pause_input_length_;
  for (std::size_t i = 0; i < n; ++i) held[i] = pause_input_[i];
  pause_input_length_ = 0;
  consume(std::string_view(held.data(), n), out);
}

void RotctldSession::feed(char c, ByteSink& out) {
  switch (state_) {
    case State::kCommand:
      // Empty lines and blanks between commands produce nothing (rotctld
      // skips CR/LF and silently ignores a blank as an unknown command).
      if (is_space(c)) return;
      if (c == '+') {
        extended_ = true;
        state_ = State::kAfterPlus;
        return;
      }
      if (is_separator(c)) {
        extended_ = true;
        separator_ = c;
        state_ = State::kAfterSeparator;
        return;
      }
      return command_char(c, out);
    case State::kAfterPlus:
      if (is_separator(c)) {
        separator_ = c;
        state_ = State::kAfterSeparator;
        return;
      }
      return command_char(c, out);
    case State::kAfterSeparator:
      return command_char(c, out);
    case State::kLongName:
      if (is_name_char(c)) {
        if (name_length_ < name_.size()) {
          name_[name_length_++] = c;
        } else {
          name_too_long_ = true;
        }
        return;
      }
      return finish_long_name(c, out);
    case State::kComment:
    case State::kDiscardLine:
      if (is_line_end(c)) state_ = State::kCommand;
      return;
    case State::kArguments:
      return argument_char(c, out);
    case State::kLineArgument:
      return line_char(c, out);
    case State::kClosed:
      return;
  }
}

void RotctldSession::command_char(char c, ByteSink& out) {
  if (is_space(c)) {
    // A prefix alone on its line (or before a blank) is dropped, as rotctld
    // drops it at the line end.
    end_command();
    return;
  }
  if (c == '\\') {
    name_length_ = 0;
    name_too_long_ = false;
    state_ = State::kLongName;
    return;
  }
  if (c == '#') {
    end_command();
    state_ = State::kComment;
    return;
  }
  if (c == 'q' || c == 'Q') {
    state_ = State::kClosed;  // the transport closes without a reply
    return;
  }
  const Command* command = rotctld::find_command(static_cast<unsigned char>(c));
  if (command == nullptr) return unknown(out, false);
  begin(*command, out);
}

void RotctldSession::finish_long_name(char terminator, ByteSink& out) {
  // rotctld consumes the character that ends the name (space, LF, ...).
  const Command* command =
      name_too_long_ ? nullptr
                     : rotctld::find_command(std::string_view(name_.data(), name_length_));
  if (command == nullptr) return unknown(out, is_line_end(terminator));
  begin(*command, out);
}

void RotctldSession::begin(const Command& command, ByteSink& out) {
  command_ = &command;
  arg_count_ = 0;
  args_used_ = 0;
  in_token_ = false;
  arg_too_long_ = false;
  line_skipped_lf_ = false;
  arg_start_[0] = 0;
  arg_length_[0] = 0;
  if (command.line_argument) {
    state_ = State::kLineArgument;
    return;
  }
  if (command.args == 0) return run(out);
  state_ = State::kArguments;
}

void RotctldSession::argument_char(char c, ByteSink& out) {
  if (is_space(c)) {
    if (!in_token_) return;  // line ends do not end a command: "P\n15\n25\n" is P 15 25
    in_token_ = false;
    ++arg_count_;
    // After a first argument starting with '?' (a list request such as
    // "V ?"), rotctld reads no further arguments.
    if (arg_count_ == command_->args || args_[arg_start_[0]] == '?') run(out);
    return;
  }
  if (!in_token_) {
    in_token_ = true;
    arg_start_[arg_count_] = static_cast<std::uint16_t>(args_used_);
    arg_length_[arg_count_] = 0;
  }
  // rotctld would overflow its 128-byte buffer here; a longer token is kept
  // short and the command fails with RPRT -1 once the token ends.
  if (arg_length_[arg_count_] < kMaxArgLength) {
    args_[args_used_++] = c;
    ++arg_length_[arg_count_];
  } else {
    arg_too_long_ = true;
  }
}

void RotctldSession::line_char(char c, ByteSink& out) {
  if (c == '\n') {
    // fgets: a line that is only LF (the command ended its line) is skipped
    // and the next line is the argument.
    if (arg_length_[0] == 0 && !line_skipped_lf_) {
      line_skipped_lf_ = true;
      return;
    }
    std::size_t start = 0;
    std::size_t length = arg_length_[0];
    if (length > 0 && args_[0] == ' ') ++start, --length;  // "w XYZ": one blank dropped
    if (length > 0 && args_[start + length - 1] == '\r') --length;
    arg_start_[0] = static_cast<std::uint16_t>(start);
    arg_length_[0] = static_cast<std::uint16_t>(length);
    arg_count_ = 1;
    return run(out);
  }
  // Beyond fgets' length rotctld parses the rest as commands; we drop it.
  if (args_used_ < kMaxLineArgLength) {
    args_[args_used_++] = c;
    arg_length_[0] = static_cast<std::uint16_t>(args_used_);
  }
}

void RotctldSession::unknown(ByteSink& out, bool line_ended) {
  // rotctld says nothing and parses the rest of the line as one-letter
  // commands; we answer once and skip the line, so a client that waits for a
  // reply gets one and stray characters cannot trigger commands.
  reply_.clear();
  reply_.format("RPRT -%d\n", static_cast<int>(HamlibError::kNotImplemented));
  out.write(reply_.view());
  end_command();
  state_ = line_ended ? State::kCommand : State::kDiscardLine;
}

std::string_view RotctldSession::arg(std::size_t i) const {
  if (i >= arg_count_) return {};
  return std::string_view(args_.data() + arg_start_[i], arg_length_[i]);
}

void RotctldSession::run(ByteSink& out) {
  const Command& command = *command_;
  reply_.clear();
  if (!command_arrives(command.op == rotctld::Op::kStop)) return end_command();
  if (extended_) {
    // First record: the command's long name and its arguments as typed.
    reply_.format("%s:", command.name);
    for (std::size_t i = 0; i < arg_count_; ++i) {
      reply_.put(' ');
      reply_.append(arg(i));
    }
    reply_.put(separator_);
  }
  // A read-only client (access.control_networks) gets RIG_ERJCTED, which
  // rotctl prints as "Command rejected by the rotator"; "V ?" only lists.
  const bool refused =
      command.changes_state && arg(0) != "?" && !may_control(controller_, command.name);
  const HamlibError e = arg_too_long_ ? HamlibError::kInvalid
                        : refused     ? HamlibError::kRejected
                                      : execute(command);
  if (e != HamlibError::kOk) {
    reply_.format("RPRT -%d\n", static_cast<int>(e));
  } else if (extended_ || !command.returns_values) {
    reply_.append("RPRT 0\n");
  }
  end_command();
  // \pause holds its reply until poll() sees the time has passed.
  if (!paused_) out.write(reply_.view());
}

void RotctldSession::end_command() {
  extended_ = false;
  separator_ = '\n';
  command_ = nullptr;
  arg_count_ = 0;
  state_ = State::kCommand;
}

rotctld::HamlibError RotctldSession::pause() {
  long seconds = 0;
  if (!rotctld::scan_whole_int(arg(0), seconds) || seconds < 0 || seconds > kMaxPauseS)
    return rotctld::HamlibError::kInvalid;
  if (seconds > 0) {
    paused_ = true;
    // On the transport's clock, from the next poll(): controller time
    // runs N times faster under `rotord --speedup N`.
    pause_started_ = false;
    pause_ms_ = static_cast<Millis>(seconds) * 1000;
  }
  return rotctld::HamlibError::kOk;
}

}  // namespace rotord::protocol
