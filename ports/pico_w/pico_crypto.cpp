// access::Crypto over the pico-sdk's mbedtls 3.x (pico_mbedtls; the config
// is config/mbedtls_config.h). The entropy comes from the SDK's
// mbedtls_hardware_poll (pico_mbedtls.c), which reads pico_rand (ring
// oscillator, timers and bus counters mixed), through mbedtls's entropy
// collector into a CTR_DRBG, as the SDK's own TLS examples seed theirs.
//
// NOT COMPILED here: this repository's CI has no pico-sdk. Written against
// mbedtls 3.6's API (pico-sdk 2.1.1 and later); the Linux implementation
// (ports/linux/mbed_crypto.cpp, mbedtls 2.28) is the tested twin.
#include "pico_crypto.hpp"

// Older mbedtls headers lack the extern "C" here; nesting it is harmless.
extern "C" {
#include <mbedtls/constant_time.h>
}

namespace rotord::pico_w {
namespace {

constexpr unsigned char kPersonalisation[] = "rotord pico w access control";

}  // namespace

PicoCrypto::PicoCrypto() {
  mbedtls_entropy_init(&entropy_);
  mbedtls_ctr_drbg_init(&drbg_);
  mbedtls_md_init(&hmac_);
}

PicoCrypto::~PicoCrypto() {
  mbedtls_md_free(&hmac_);
  mbedtls_ctr_drbg_free(&drbg_);
  mbedtls_entropy_free(&entropy_);
}

bool PicoCrypto::begin() {
  const mbedtls_md_info_t* sha256 = mbedtls_md_info_from_type(MBEDTLS_MD_SHA256);
  ready_ = sha256 != nullptr && mbedtls_md_setup(&hmac_, sha256, 1) == 0 &&
           mbedtls_ctr_drbg_seed(&drbg_, mbedtls_entropy_func, &entropy_, kPersonalisation,
                                 sizeof kPersonalisation - 1) == 0;
  return ready_;
}

bool PicoCrypto::random(std::span<std::uint8_t> out) {
  if (!ready_) return false;
  while (!out.empty()) {
    const std::size_t n =
        out.size() < MBEDTLS_CTR_DRBG_MAX_REQUEST ? out.size() : MBEDTLS_CTR_DRBG_MAX_REQUEST;
    if (mbedtls_ctr_drbg_random(&drbg_, out.data(), n) != 0) return false;
    out = out.subspan(n);
  }
  return true;
}

bool PicoCrypto::hmac_sha256(std::span<const std::uint8_t> key,
                             std::span<const std::uint8_t> message, access::Sha256Digest& out) {
  return ready_ && mbedtls_md_hmac_starts(&hmac_, key.data(), key.size()) == 0 &&
         mbedtls_md_hmac_update(&hmac_, message.data(), message.size()) == 0 &&
         mbedtls_md_hmac_finish(&hmac_, out.data()) == 0;
}

bool PicoCrypto::equal(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b) const {
  return a.size() == b.size() && mbedtls_ct_memcmp(a.data(), b.data(), a.size()) == 0;
}

}  // namespace rotord::pico_w
