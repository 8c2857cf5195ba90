#include "log_port.hpp"

#include <algorithm>
#include <cstdio>

namespace rotord::usb_port {

void LogPort::write(std::string_view bytes) {
  if (bytes.empty()) return;
  // Straight out only when nothing older waits, so the order is kept.
  if (listening() && size_ == 0 && untold_dropped_ == 0) {
    bytes.remove_prefix(send(bytes));
    port_.flush();
  }
  keep(bytes);
}

void LogPort::write_live(std::string_view bytes) {
  if (!listening()) {
    stats_.unheard_bytes += static_cast<std::uint32_t>(bytes.size());
    return;
  }
  write(bytes);
}

void LogPort::attach_console(protocol::Session& console) {
  console_ = &console;
  console_->set_peer(access::Peer::line());
}

void LogPort::serve_console() {
  // A listing still going out first: input waits until it is done.
  if (console_->output_pending()) {
    console_->write_more(kRingBytes - size_, *this);
    if (console_->output_pending()) return;
  }
  std::array<char, UsbCdcLink::kReadChunkBytes> chunk{};
  std::size_t budget = kMaxConsoleInputPerService;
  while (budget > 0 && !console_->output_pending()) {
    const std::size_t n = port_.read(chunk.data(), std::min(budget, chunk.size()));
    if (n == 0) break;
    budget -= n;
    console_->receive(std::string_view(chunk.data(), n), *this);
    if (console_->output_pending()) console_->write_more(kRingBytes - size_, *this);
  }
}

void LogPort::service() {
  if (console_ != nullptr) {
    serve_console();
  } else {
    port_.discard_input();
  }
  if (!listening()) return;
  bool sent = false;
  if (untold_dropped_ > 0) {
    // Before the ring's contents: what was dropped is older than all of it.
    char note[96];
    const int length = std::snprintf(note, sizeof note,
                                     "rotord: log: %lu bytes of older lines dropped (the log "
                                     "port was not read)\r\n",
                                     static_cast<unsigned long>(untold_dropped_));
    const std::size_t note_bytes = std::min(sizeof note - 1, static_cast<std::size_t>(length));
    if (port_.write_available() < note_bytes) return;  // whole, on a later pass
    send(std::string_view(note, note_bytes));
    untold_dropped_ = 0;
    sent = true;
  }
  while (size_ > 0) {
    const std::size_t n = send(first_piece());
    if (n == 0) break;
    head_ = (head_ + n) % kRingBytes;
    size_ -= n;
    sent = true;
  }
  if (sent) port_.flush();
}

std::size_t LogPort::send(std::string_view bytes) {
  const std::size_t n = port_.write(bytes.data(), std::min(bytes.size(), port_.write_available()));
  stats_.sent_bytes += static_cast<std::uint32_t>(n);
  return n;
}

void LogPort::keep(std::string_view bytes) {
  if (bytes.empty()) return;
  if (bytes.size() >= kRingBytes) {
    // One write larger than the ring: only its end fits.
    drop_oldest(size_);
    const std::size_t skipped = bytes.size() - kRingBytes;
    stats_.dropped_bytes += static_cast<std::uint32_t>(skipped);
    untold_dropped_ += static_cast<std::uint32_t>(skipped);
    bytes.remove_prefix(skipped);
  } else if (size_ + bytes.size() > kRingBytes) {
    drop_oldest(size_ + bytes.size() - kRingBytes);
  }
  std::size_t tail = (head_ + size_) % kRingBytes;
  for (char c : bytes) {
    ring_[tail] = c;
    tail = tail + 1 == kRingBytes ? 0 : tail + 1;
  }
  size_ += bytes.size();
}

void LogPort::drop_oldest(std::size_t bytes) {
  // On to the end of the line the cut falls in, so the next reader starts
  // on a whole line.
  std::size_t dropped = std::min(bytes, size_);
  if (dropped > 0) {
    while (dropped < size_ && ring_[(head_ + dropped - 1) % kRingBytes] != '\n') ++dropped;
  }
  head_ = (head_ + dropped) % kRingBytes;
  size_ -= dropped;
  stats_.dropped_bytes += static_cast<std::uint32_t>(dropped);
  untold_dropped_ += static_cast<std::uint32_t>(dropped);
}

std::string_view LogPort::first_piece() const {
  return std::string_view(ring_.data() + head_, std::min(size_, kRingBytes - head_));
}

}  // namespace rotord::usb_port
