#pragma once
// A real Mosquitto broker for the MQTT tests (the daemon's libmosquitto
// client and the Pico W's lwIP client): started in a directory of the
// test's, killed when the object goes.
#include <sys/types.h>

#include <string>

namespace rotord::testing {

class MosquittoBroker {
 public:
  /// `address`, `port`: where it listens. `conf`: the rest of mosquitto.conf.
  /// `ping_args`: the mosquitto_pub options that reach it (host, port, login),
  /// used to wait until it answers.
  MosquittoBroker(const std::string& dir, const std::string& address, int port,
                  const std::string& conf, const std::string& ping_args);
  ~MosquittoBroker();
  MosquittoBroker(const MosquittoBroker&) = delete;
  MosquittoBroker& operator=(const MosquittoBroker&) = delete;

  /// Starts it (again, after stop()) and waits, bounded, until a client can
  /// publish.
  void start();
  /// SIGKILL: no goodbye to its clients, as a crash or a power cut.
  void stop();
  pid_t pid() const { return pid_; }

 private:
  std::string dir_;
  std::string address_;
  int port_;
  std::string conf_;
  std::string ping_args_;
  pid_t pid_ = -1;
};

}  // namespace rotord::testing
