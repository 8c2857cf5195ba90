#include "sensors/magnetometer.hpp"

#include <cmath>

#include "motion/angles.hpp"

namespace rotord {
namespace {

// QMC5883L registers (QST datasheet): data X/Y/Z LSB first at 0x00, status
// 0x06 (DRDY, OVL, DOR), control 1 0x09, control 2 0x0A, SET/RESET period
// 0x0B, chip id 0x0D = 0xFF.
constexpr std::uint8_t kQmcData = 0x00;
constexpr std::uint8_t kQmcStatus = 0x06;
constexpr std::uint8_t kQmcControl1 = 0x09;
constexpr std::uint8_t kQmcSetReset = 0x0B;
constexpr std::uint8_t kQmcChipId = 0x0D;
constexpr std::uint8_t kQmcStatusOverflow = 0x02;
// Continuous mode, 50 Hz (the tick polls at 100 Hz), 8 gauss range (a mast
// clamp or motor nearby must not saturate it), 512x oversampling.
constexpr std::uint8_t kQmcContinuous50Hz8G = 0x01 | 0x04 | 0x10 | 0x00;

// HMC5883L registers (Honeywell datasheet): config A 0x00, B 0x01, mode
// 0x02, data X, Z, Y (MSB first) at 0x03, id 0x0A..0x0C = "H43".
constexpr std::uint8_t kHmcConfigA = 0x00;
constexpr std::uint8_t kHmcConfigB = 0x01;
constexpr std::uint8_t kHmcMode = 0x02;
constexpr std::uint8_t kHmcData = 0x03;
constexpr std::uint8_t kHmcId = 0x0A;
constexpr std::uint8_t kHmcAverage8At15Hz = 0x70;
constexpr std::uint8_t kHmcGain1_3Ga = 0x20;
constexpr std::uint8_t kHmcContinuous = 0x00;
constexpr std::int16_t kHmcOverflow = -4096;

std::int16_t le16(const std::uint8_t* p) {
  return static_cast<std::int16_t>(static_cast<std::uint16_t>(p[0] | (p[1] << 8)));
}
std::int16_t be16(const std::uint8_t* p) {
  return static_cast<std::int16_t>(static_cast<std::uint16_t>((p[0] << 8) | p[1]));
}

}  // namespace

void Magnetometer::set_chip(MagChip chip) {
  if (chip != chip_) started_ = false;
  chip_ = chip;
}

Magnetometer::Status Magnetometer::begin() {
  started_ = false;
  if (chip_ == MagChip::kQmc5883l) {
    std::uint8_t id = 0;
    if (!bus_.read_registers(kQmcAddress, kQmcChipId, &id, 1)) return Status::kNoAnswer;
    if (id != 0xFF) return Status::kWrongChip;
    if (!bus_.write_register(kQmcAddress, kQmcSetReset, 0x01) ||
        !bus_.write_register(kQmcAddress, kQmcControl1, kQmcContinuous50Hz8G))
      return Status::kNoAnswer;
  } else {
    std::uint8_t id[3] = {};
    if (!bus_.read_registers(kHmcAddress, kHmcId, id, 3)) return Status::kNoAnswer;
    if (id[0] != 'H' || id[1] != '4' || id[2] != '3') return Status::kWrongChip;
    if (!bus_.write_register(kHmcAddress, kHmcConfigA, kHmcAverage8At15Hz) ||
        !bus_.write_register(kHmcAddress, kHmcConfigB, kHmcGain1_3Ga) ||
        !bus_.write_register(kHmcAddress, kHmcMode, kHmcContinuous))
      return Status::kNoAnswer;
  }
  started_ = true;
  return Status::kOk;
}

Magnetometer::Status Magnetometer::read(MagSample& out) {
  if (!started_) {
    const Status s = begin();
    if (s != Status::kOk) return s;
  }
  if (chip_ == MagChip::kQmc5883l) {
    // Data and status in one burst (0x00..0x06).
    std::uint8_t r[7] = {};
    if (!bus_.read_registers(kQmcAddress, kQmcData, r, sizeof r)) {
      started_ = false;
      return Status::kNoAnswer;
    }
    static_assert(kQmcStatus == kQmcData + 6);
    out = {le16(r), le16(r + 2), le16(r + 4)};
    if ((r[6] & kQmcStatusOverflow) != 0) return Status::kOverflow;
    return Status::kOk;
  }
  std::uint8_t r[6] = {};
  if (!bus_.read_registers(kHmcAddress, kHmcData, r, sizeof r)) {
    started_ = false;
    return Status::kNoAnswer;
  }
  out = {be16(r), be16(r + 4), be16(r + 2)};  // the registers go X, Z, Y
  if (out.x == kHmcOverflow || out.y == kHmcOverflow || out.z == kHmcOverflow)
    return Status::kOverflow;
  return Status::kOk;
}

std::optional<float> mag_heading_deg(const MagSample& sample, const MagCalibration& cal) {
  if (!cal.valid()) return std::nullopt;
  const float x = (static_cast<float>(sample.x) - 0.5f * (cal.x_max + cal.x_min)) /
                  (0.5f * (cal.x_max - cal.x_min));
  const float y = (static_cast<float>(sample.y) - 0.5f * (cal.y_max + cal.y_min)) /
                  (0.5f * (cal.y_max - cal.y_min));
  // After scaling a good sample lies near the unit circle.
  if (x * x + y * y < 0.25f * 0.25f) return std::nullopt;
  float deg = std::atan2(y, x) * (180.0f / 3.14159265f);
  if (cal.reverse) deg = -deg;
  return wrap_360(deg + cal.declination_deg);
}

float HeadingFilter::step(float heading_deg) {
  if (!have_) {
    have_ = true;
    out_deg_ = wrap_360(heading_deg);
    return out_deg_;
  }
  const float near = unwrap_near(heading_deg, out_deg_);
  out_deg_ = wrap_360(out_deg_ + alpha_ * (near - out_deg_));
  return out_deg_;
}

}  // namespace rotord
