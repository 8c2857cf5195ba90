#pragma once
// Tracking clients modelled from their sources, in process over a protocol
// session (header-only: the bench rows and the sim scenario tests drive the
// same models).
// - Gpredict (src/gtk-rot-ctrl.c): a cycle of about 0.8-1 s reads `p` and
//   sends `P az el` when off by more than its threshold (5 deg) on either
//   axis, compared with plain fabs; azimuths 0..360 from its predictor.
//   With max el 180 configured, a pass whose 0..360 azimuth track jumps
//   across north (is_flipped_pass) is sent flipped whole: az +/- 180 into
//   0..360, 180 - el.
// - The SatNOGS client (satnogs_client/rotator worker): every 3 s, a new
//   position when off by more than 4 deg, comparing against azimuth % 360;
//   with SATNOGS_ROT_FLIP and a culmination at or above 75 deg, past the
//   culmination it mirrors the pass: az = 2 az_mid - az, el = 2 el_mid - el
//   (up to ~180), normalised to 0..360.
// - A SatDump-like client: every second, no threshold of its own.
#include <cmath>
#include <cstdio>
#include <string>
#include <string_view>

#include "protocol/session.hpp"

namespace rotord::bench {

struct SkyAzEl {
  double az_deg = 0;  ///< 0..360
  double el_deg = 0;
};

enum class ClientKind { kGpredict, kSatnogs, kSatdump };

inline const char* client_name(ClientKind kind) {
  switch (kind) {
    case ClientKind::kGpredict:
      return "gpredict";
    case ClientKind::kSatnogs:
      return "satnogs";
    case ClientKind::kSatdump:
      return "satdump";
  }
  return "?";
}

/// What the client knows of the pass before it starts (its own predictor).
struct ClientPass {
  bool flip = false;  ///< the client flips this pass (its rule, its setting)
  SkyAzEl culmination;
  double culmination_s = 0;  ///< from the start of the run
};

/// One modelled client. step() is called every control tick with the
/// satellite's true position; it talks to `session` when its cycle is due.
class TrackerClient {
 public:
  explicit TrackerClient(ClientKind kind, ClientPass pass = {}) : kind_(kind), pass_(pass) {
    cycle_ms_ = kind == ClientKind::kSatnogs ? 3000 : (kind == ClientKind::kGpredict ? 900 : 1000);
    threshold_deg_ =
        kind == ClientKind::kSatnogs ? 4.0 : (kind == ClientKind::kGpredict ? 5.0 : 0.0);
  }
  /// Where the client wants the antenna for a sky position at `t_s`.
  SkyAzEl wanted(SkyAzEl sky, double t_s) const {
    if (!pass_.flip) return sky;
    if (kind_ == ClientKind::kGpredict) {
      SkyAzEl w{sky.az_deg < 180.0 ? sky.az_deg + 180.0 : sky.az_deg - 180.0, 180.0 - sky.el_deg};
      return w;
    }
    if (kind_ == ClientKind::kSatnogs && t_s >= pass_.culmination_s) {
      const double az = 2.0 * pass_.culmination.az_deg - sky.az_deg;
      const double el = 2.0 * pass_.culmination.el_deg - sky.el_deg;
      return {std::fmod(std::fmod(az, 360.0) + 360.0, 360.0), el};
    }
    return sky;
  }
  void step(long long now_ms, SkyAzEl sky, protocol::Session& session) {
    if (now_ms < next_ms_) return;
    next_ms_ = now_ms + cycle_ms_;
    const SkyAzEl w = wanted(sky, static_cast<double>(now_ms) / 1000.0);
    const std::string reply = ask(session, "p\n");
    double az = 0, el = 0;
    if (std::sscanf(reply.c_str(), "%lf %lf", &az, &el) != 2) return;
    if (kind_ == ClientKind::kSatnogs) az = std::fmod(az, 360.0);
    const double w_el = w.el_deg < 0.0 ? 0.0 : w.el_deg;
    if (std::fabs(w.az_deg - az) <= threshold_deg_ && std::fabs(w_el - el) <= threshold_deg_ &&
        threshold_deg_ > 0.0)
      return;
    char cmd[64];
    std::snprintf(cmd, sizeof cmd, "P %.2f %.2f\n", w.az_deg, w_el);
    ++commands_;
    if (ask(session, cmd) != "RPRT 0\n") ++refused_;
  }
  /// The error it lets stand before sending (0: none, a go-to every cycle).
  double threshold_deg() const { return threshold_deg_; }
  /// How often it looks.
  long long cycle_ms() const { return cycle_ms_; }
  /// Whether it would send, off by `d_az_deg` / `d_el_deg` from its wish.
  bool would_send(double d_az_deg, double d_el_deg) const {
    return threshold_deg_ <= 0.0 || std::fabs(d_az_deg) > threshold_deg_ ||
           std::fabs(d_el_deg) > threshold_deg_;
  }
  int commands() const { return commands_; }
  int refused() const { return refused_; }

 private:
  class Sink final : public protocol::ByteSink {
   public:
    void write(std::string_view bytes) override { data.append(bytes); }
    std::string data;
  };
  static std::string ask(protocol::Session& session, const char* line) {
    Sink sink;
    session.receive(line, sink);
    return sink.data;
  }

  ClientKind kind_;
  ClientPass pass_;
  long long cycle_ms_ = 1000;
  double threshold_deg_ = 0;
  long long next_ms_ = 0;
  int commands_ = 0;
  int refused_ = 0;
};

}  // namespace rotord::bench
