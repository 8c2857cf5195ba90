#pragma once
#include <mbedtls/ctr_drbg.h>
#include <mbedtls/entropy.h>
#include <mbedtls/md.h>

#include "access/crypto.hpp"

namespace rotord::linux_port {

/// access::Crypto over Debian's mbedtls 2.28 (libmbedcrypto): a CTR_DRBG
/// seeded from mbedtls's entropy collector (getrandom / /dev/urandom),
/// HMAC-SHA256 through the md layer, mbedtls_ct_memcmp. One per daemon, used
/// from the asio thread only.
class MbedCrypto final : public access::Crypto {
 public:
  MbedCrypto();
  ~MbedCrypto() override;
  MbedCrypto(const MbedCrypto&) = delete;
  MbedCrypto& operator=(const MbedCrypto&) = delete;

  /// False when the generator could not be seeded or the md layer set up;
  /// every call then fails (access control refuses what needs it).
  bool ready() const { return ready_; }

  bool random(std::span<std::uint8_t> out) override;
  bool hmac_sha256(std::span<const std::uint8_t> key, std::span<const std::uint8_t> message,
                   access::Sha256Digest& out) override;
  bool equal(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b) const override;

 private:
  mbedtls_entropy_context entropy_;
  mbedtls_ctr_drbg_context drbg_;
  mbedtls_md_context_t hmac_;
  bool ready_ = false;
};

}  // namespace rotord::linux_port
