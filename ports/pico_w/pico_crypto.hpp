#pragma once
// access::Crypto on the Pico W, over the pico-sdk's mbedtls (3.x): see
// pico_crypto.cpp. NOT COMPILED in this repository's CI (no pico-sdk here);
// written against mbedtls 3.6's API.
#include <mbedtls/ctr_drbg.h>
#include <mbedtls/entropy.h>
#include <mbedtls/md.h>

#include "access/crypto.hpp"

namespace rotord::pico_w {

class PicoCrypto final : public access::Crypto {
 public:
  PicoCrypto();
  ~PicoCrypto() override;
  PicoCrypto(const PicoCrypto&) = delete;
  PicoCrypto& operator=(const PicoCrypto&) = delete;

  /// Seeds the generator and sets up HMAC (its one heap allocation, at
  /// start-up). False when either fails: web logins are then refused.
  bool begin();
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

}  // namespace rotord::pico_w
