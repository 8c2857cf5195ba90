// mbedtls for the Pico W firmware (the pico-sdk's copy, 3.6.x in SDK 2.2):
// only what access control uses (pico_crypto.cpp): HMAC-SHA256 through the
// md layer, a CTR_DRBG seeded by mbedtls's entropy collector from the SDK's
// hardware source (mbedtls_hardware_poll in pico_mbedtls.c, over pico_rand),
// and the constant-time compare. No TLS, no X.509, no bignum.
// The SDK's pico_mbedtls_config.h includes this file (MBEDTLS_CONFIG_FILE).
#ifndef ROTORD_MBEDTLS_CONFIG_H
#define ROTORD_MBEDTLS_CONFIG_H

// Entropy: the SDK's hardware poll only (no /dev/urandom on the chip).
#define MBEDTLS_NO_PLATFORM_ENTROPY
#define MBEDTLS_ENTROPY_HARDWARE_ALT
#define MBEDTLS_ENTROPY_C
#define MBEDTLS_ENTROPY_FORCE_SHA256  // no SHA-512 in this build

// The generator: CTR_DRBG over AES-256.
#define MBEDTLS_CTR_DRBG_C
#define MBEDTLS_AES_C
#define MBEDTLS_AES_ROM_TABLES    // tables in flash, not 8 KB of RAM
#define MBEDTLS_AES_FEWER_TABLES  // and only 2 KB of them

// HMAC-SHA256 (the md layer). Not MBEDTLS_SHA256_SMALLER: its rolled loop
// shuffles the working variables through RAM every round, and the password
// hash's time per login matters more than a kilobyte of flash.
#define MBEDTLS_MD_C
#define MBEDTLS_SHA256_C
#define MBEDTLS_SHA224_C  // mbedtls 3.x builds SHA-224 with SHA-256's code

#endif  // ROTORD_MBEDTLS_CONFIG_H
