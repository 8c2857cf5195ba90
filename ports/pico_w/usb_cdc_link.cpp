#include "usb_cdc_link.hpp"

#include <algorithm>
#include <cstring>

namespace rotord::usb_port {

UsbCdcLink::UsbCdcLink(CdcPort& port, SessionMaker& sessions)
    : port_(port), sessions_(sessions), opens_(port.opens()) {
  session_ = &sessions_.renew();
  session_->set_peer(access::Peer::line());
  ++stats_.sessions;
}

void UsbCdcLink::restart(bool drop_input) {
  session_ = &sessions_.renew();
  session_->set_peer(access::Peer::line());
  ++stats_.sessions;
  heard_ = false;
  head_ = tail_ = 0;
  port_.discard_output();
  if (drop_input) port_.discard_input();
}

void UsbCdcLink::service() {
  const bool was_connected = connected_;
  const bool had_dtr = dtr_;
  connected_ = port_.connected();
  dtr_ = connected_ && port_.dtr();

  // A program opened the port since the last pass (perhaps closing and
  // reopening it in between): it gets a session of its own. Its first bytes
  // may already be in the FIFO, so input is kept.
  const std::uint32_t opens = port_.opens();
  const bool opened = opens != opens_;
  if (opened) {
    opens_ = opens;
    restart(false);
  }

  // Output first, to make room for the replies to the input.
  pump_output();
  // Input next: a program that sends a command and closes at once (a
  // shell's `printf ... > /dev/ttyACM1`) still has it executed.
  if (connected_) pump_input();

  // The program closed the port (or came and went between two passes) or
  // the host went away: whatever it left half-sent or unread belongs to
  // nobody.
  if (((had_dtr || opened) && !dtr_) || (was_connected && !connected_)) restart(true);

  pump_output();
}

void UsbCdcLink::poll(Millis now) {
  if (!connected_) return;
  session_->poll(now, *this);
  if (session_->wants_close()) restart(false);
}

void UsbCdcLink::pump_input() {
  // A long reply still going out (the console's listings) first, in pieces
  // the buffer takes whole; input waits in the FIFO until it is done.
  continue_reply();
  std::array<char, kReadChunkBytes> chunk{};
  std::size_t budget = kMaxInputBytesPerService;
  while (budget > 0 && !session_->output_pending()) {
    const std::size_t n = port_.read(chunk.data(), std::min(budget, chunk.size()));
    if (n == 0) break;
    budget -= n;
    stats_.received_bytes += static_cast<std::uint32_t>(n);
    heard_ = true;
    session_->receive(std::string_view(chunk.data(), n), *this);
    continue_reply();
    // A session that ends itself (rotctld `q`) starts afresh: the line
    // stays, as on Linux's serial transport.
    if (session_->wants_close()) {
      session_ = &sessions_.renew();
      session_->set_peer(access::Peer::line());
      ++stats_.sessions;
    }
  }
}

void UsbCdcLink::continue_reply() {
  if (!session_->output_pending()) return;
  const std::size_t room = pending_.size() - pending_bytes();
  if (room > 0) session_->write_more(room, *this);
}

void UsbCdcLink::write(std::string_view bytes) {
  if (bytes.empty()) return;
  if (!listening()) {
    stats_.unheard_bytes += static_cast<std::uint32_t>(bytes.size());
    return;
  }
  // Earlier output still waiting keeps its place in front.
  if (head_ == tail_ && bytes.size() <= port_.write_available()) {
    const std::size_t n = port_.write(bytes.data(), bytes.size());
    stats_.sent_bytes += static_cast<std::uint32_t>(n);
    bytes.remove_prefix(n);
    port_.flush();
    if (bytes.empty()) return;
    // The port took less than it offered: the rest waits in the buffer
    // (room for it is certain, the buffer was empty).
  }
  if (!append_pending(bytes)) {
    ++stats_.dropped_replies;
    stats_.dropped_bytes += static_cast<std::uint32_t>(bytes.size());
    return;
  }
  pump_output();
}

bool UsbCdcLink::append_pending(std::string_view bytes) {
  if (bytes.size() > pending_.size() - pending_bytes()) return false;
  if (bytes.size() > pending_.size() - tail_) {
    // Move the waiting bytes to the front to make the room contiguous.
    std::memmove(pending_.data(), pending_.data() + head_, pending_bytes());
    tail_ -= head_;
    head_ = 0;
  }
  std::memcpy(pending_.data() + tail_, bytes.data(), bytes.size());
  tail_ += bytes.size();
  return true;
}

void UsbCdcLink::pump_output() {
  if (head_ == tail_) return;
  if (!listening()) {
    // The listener left with output still waiting.
    stats_.unheard_bytes += static_cast<std::uint32_t>(pending_bytes());
    head_ = tail_ = 0;
    return;
  }
  const std::size_t room = std::min(port_.write_available(), pending_bytes());
  if (room == 0) return;
  const std::size_t n = port_.write(pending_.data() + head_, room);
  stats_.sent_bytes += static_cast<std::uint32_t>(n);
  head_ += n;
  if (head_ == tail_) head_ = tail_ = 0;
  port_.flush();
}

}  // namespace rotord::usb_port
