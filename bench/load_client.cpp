// Closed-loop load client for line protocols over real loopback sockets:
// N clients, each sending one request and reading the whole reply before the
// next, for a fixed wall-clock duration. Compiled (a Python client saturates
// near 30 000 requests/s and would measure itself).
//
//   rotord_load_client PORT CLIENTS SECONDS [REQUEST [REPLY_LINES]]
//
// Defaults: request "p\n" (rotctld get_pos), reply of 2 lines. Prints one JSON
// object: requests, requests_per_s, median_us, p99_us, errors.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

struct ClientResult {
  std::vector<float> latencies_us;
  long errors = 0;
};

int connect_to(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return -1;
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
    ::close(fd);
    return -1;
  }
  const int one = 1;
  ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  timeval tv{5, 0};  // a server that stops answering ends the client, not the run
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  return fd;
}

// Reads until `lines` newlines arrived; false on EOF, error or timeout.
bool read_reply(int fd, int lines) {
  char buf[512];
  int seen = 0;
  while (seen < lines) {
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    if (n <= 0) return false;
    seen += static_cast<int>(std::count(buf, buf + n, '\n'));
  }
  return true;
}

void run_client(int port, const std::string& request, int reply_lines, Clock::time_point start,
                Clock::time_point end, ClientResult* out) {
  const int fd = connect_to(port);
  if (fd < 0) {
    ++out->errors;
    return;
  }
  while (Clock::now() < start) std::this_thread::yield();
  while (true) {
    const auto t0 = Clock::now();
    if (t0 >= end) break;
    if (::send(fd, request.data(), request.size(), MSG_NOSIGNAL) !=
            static_cast<ssize_t>(request.size()) ||
        !read_reply(fd, reply_lines)) {
      ++out->errors;
      break;
    }
    out->latencies_us.push_back(
        std::chrono::duration<float, std::micro>(Clock::now() - t0).count());
  }
  ::close(fd);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s PORT CLIENTS SECONDS [REQUEST [REPLY_LINES]]\n", argv[0]);
    return 2;
  }
  const int port = std::atoi(argv[1]);
  const int clients = std::atoi(argv[2]);
  const double seconds = std::atof(argv[3]);
  std::string request = argc > 4 ? argv[4] : "p";
  request += "\n";
  const int reply_lines = argc > 5 ? std::atoi(argv[5]) : 2;
  if (port <= 0 || clients <= 0 || seconds <= 0 || reply_lines <= 0) {
    std::fprintf(stderr, "bad arguments\n");
    return 2;
  }
  std::vector<ClientResult> results(static_cast<std::size_t>(clients));
  std::vector<std::thread> threads;
  // Everyone connects first, then the measured window opens for all at once.
  const auto start = Clock::now() + std::chrono::milliseconds(300 + 5 * clients);
  const auto end =
      start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  for (int i = 0; i < clients; ++i)
    threads.emplace_back(run_client, port, request, reply_lines, start, end,
                         &results[static_cast<std::size_t>(i)]);
  for (auto& t : threads) t.join();
  std::vector<float> all;
  long errors = 0;
  for (const auto& r : results) {
    all.insert(all.end(), r.latencies_us.begin(), r.latencies_us.end());
    errors += r.errors;
  }
  std::sort(all.begin(), all.end());
  auto pct = [&](double q) {
    return all.empty()
               ? 0.0
               : static_cast<double>(
                     all[static_cast<std::size_t>(q * static_cast<double>(all.size() - 1))]);
  };
  std::printf(
      "{\"requests\": %zu, \"requests_per_s\": %.1f, \"median_us\": %.1f, \"p99_us\": %.1f, "
      "\"errors\": %ld}\n",
      all.size(), static_cast<double>(all.size()) / seconds, pct(0.5), pct(0.99), errors);
  return 0;
}
