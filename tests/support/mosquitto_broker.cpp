#include "mosquitto_broker.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>

#include "shell.hpp"

namespace rotord::testing {

MosquittoBroker::MosquittoBroker(const std::string& dir, const std::string& address, int port,
                                 const std::string& conf, const std::string& ping_args)
    : dir_(dir), address_(address), port_(port), conf_(conf), ping_args_(ping_args) {
  start();
}

MosquittoBroker::~MosquittoBroker() {
  stop();
}

void MosquittoBroker::start() {
  const std::string conf = dir_ + "/mosquitto.conf";
  std::ofstream(conf) << "listener " << port_ << " " << address_ << "\n" << conf_;
  pid_ = ::fork();
  if (pid_ == 0) {
    // Its log goes to a file in the test's directory, not the test output.
    const int log = ::open((dir_ + "/mosquitto.log").c_str(), O_WRONLY | O_CREAT | O_APPEND, 0600);
    if (log >= 0) {
      ::dup2(log, 1);
      ::dup2(log, 2);
    }
    ::execlp("mosquitto", "mosquitto", "-c", conf.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Ready when a client can publish (bounded; liveness only).
  run_command("for i in $(seq 100); do mosquitto_pub " + ping_args_ +
              " -t rotord-test/ping -n 2>/dev/null && break; sleep 0.05; done");
}

void MosquittoBroker::stop() {
  if (pid_ <= 0) return;
  ::kill(pid_, SIGKILL);
  ::waitpid(pid_, nullptr, 0);
  pid_ = -1;
}

}  // namespace rotord::testing
