#include "mbed_crypto.hpp"

// mbedtls 2.28's constant_time.h lacks the extern "C" its other headers have.
extern "C" {
#include <mbedtls/constant_time.h>
}

namespace rotord::linux_port {
namespace {

constexpr unsigned char kPersonalisation[] = "rotord access control";

}  // namespace

MbedCrypto::MbedCrypto() {
  mbedtls_entropy_init(&entropy_);
  mbedtls_ctr_drbg_init(&drbg_);
  mbedtls_md_init(&hmac_);
  const mbedtls_md_info_t* sha256 = mbedtls_md_info_from_type(MBEDTLS_MD_SHA256);
  ready_ = sha256 != nullptr && mbedtls_md_setup(&hmac_, sha256, 1) == 0 &&
           mbedtls_ctr_drbg_seed(&drbg_, mbedtls_entropy_func, &entropy_, kPersonalisation,
                                 sizeof kPersonalisation - 1) == 0;
}

MbedCrypto::~MbedCrypto() {
  mbedtls_md_free(&hmac_);
  mbedtls_ctr_drbg_free(&drbg_);
  mbedtls_entropy_free(&entropy_);
}

bool MbedCrypto::random(std::span<std::uint8_t> out) {
  if (!ready_) return false;
  // The DRBG hands out at most MBEDTLS_CTR_DRBG_MAX_REQUEST bytes per call.
  while (!out.empty()) {
    const std::size_t n =
        out.size() < MBEDTLS_CTR_DRBG_MAX_REQUEST ? out.size() : MBEDTLS_CTR_DRBG_MAX_REQUEST;
    if (mbedtls_ctr_drbg_random(&drbg_, out.data(), n) != 0) return false;
    out = out.subspan(n);
  }
  return true;
}

bool MbedCrypto::hmac_sha256(std::span<const std::uint8_t> key,
                             std::span<const std::uint8_t> message, access::Sha256Digest& out) {
  return ready_ && mbedtls_md_hmac_starts(&hmac_, key.data(), key.size()) == 0 &&
         mbedtls_md_hmac_update(&hmac_, message.data(), message.size()) == 0 &&
         mbedtls_md_hmac_finish(&hmac_, out.data()) == 0;
}

bool MbedCrypto::equal(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b) const {
  // The lengths are public (fixed sizes of ids and hashes); the contents are not.
  return a.size() == b.size() && mbedtls_ct_memcmp(a.data(), b.data(), a.size()) == 0;
}

}  // namespace rotord::linux_port
