#include "access/pbkdf2.hpp"

#include <cstring>

namespace rotord::access {

void Pbkdf2::clear() {
  // volatile: the wipe must not be optimised away as a dead store.
  volatile std::uint8_t* p = password_;
  for (std::size_t n = 0; n < sizeof password_; ++n) p[n] = 0;
  password_bytes_ = 0;
  u_ = {};
  t_ = {};
  done_ = 0;
  iterations_ = 0;
  status_ = Status::kIdle;
}

void Pbkdf2::start(std::string_view password, std::span<const std::uint8_t> salt,
                   std::uint32_t iterations) {
  clear();
  if (password.size() > kMaxPasswordBytes || salt.size() > kMaxSaltBytes || iterations == 0) {
    status_ = Status::kFailed;
    return;
  }
  std::memcpy(password_, password.data(), password.size());
  password_bytes_ = password.size();
  std::memcpy(salt_block_, salt.data(), salt.size());
  // INT(1): the first (and only) block's index, big-endian.
  salt_block_[salt.size()] = 0;
  salt_block_[salt.size() + 1] = 0;
  salt_block_[salt.size() + 2] = 0;
  salt_block_[salt.size() + 3] = 1;
  salt_block_bytes_ = salt.size() + 4;
  iterations_ = iterations;
  status_ = Status::kRunning;
}

Pbkdf2::Status Pbkdf2::step(Crypto& crypto, std::uint32_t max_iterations) {
  if (status_ != Status::kRunning) return status_;
  const std::span<const std::uint8_t> key(password_, password_bytes_);
  if (max_iterations == 0) max_iterations = 1;
  for (std::uint32_t n = 0; n < max_iterations && done_ < iterations_; ++n) {
    // U1 = PRF(P, S || INT(1)); Ui = PRF(P, Ui-1); T = U1 ^ U2 ^ ... ^ Uc.
    Sha256Digest next;
    const bool ok = done_ == 0 ? crypto.hmac_sha256(key, {salt_block_, salt_block_bytes_}, next)
                               : crypto.hmac_sha256(key, u_, next);
    u_ = next;
    if (!ok) {
      clear();
      status_ = Status::kFailed;
      return status_;
    }
    for (std::size_t b = 0; b < t_.size(); ++b) t_[b] = done_ == 0 ? u_[b] : t_[b] ^ u_[b];
    ++done_;
  }
  if (done_ == iterations_) {
    // Keep the key, forget the password.
    const Sha256Digest key_out = t_;
    const std::uint32_t done = done_;
    clear();
    t_ = key_out;
    done_ = done;
    status_ = Status::kDone;
  }
  return status_;
}

}  // namespace rotord::access
