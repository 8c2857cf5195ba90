#include "rotator/goto_match.hpp"

#include <cmath>

#include "motion/angles.hpp"

namespace rotord {
namespace {

constexpr float kDeg2Rad = 3.14159265f / 180.0f;

struct Vec3 {
  float x, y, z;
};

Vec3 unit(float az_deg, float el_deg) {
  const float az = az_deg * kDeg2Rad;
  const float el = el_deg * kDeg2Rad;
  return {std::cos(el) * std::sin(az), std::cos(el) * std::cos(az), std::sin(el)};
}

float dot(const Vec3& a, const Vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

Vec3 sub(const Vec3& a, const Vec3& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}

Vec3 along(const Vec3& p, const Vec3& v, float s) {
  return {p.x + v.x * s, p.y + v.y * s, p.z + v.z * s};
}

/// The angle subtended by a chord of length `d` on the unit sphere.
float chord_to_deg(float d) {
  const float half = d > 2.0f ? 1.0f : 0.5f * d;
  return 2.0f * std::asin(half) / kDeg2Rad;
}

}  // namespace

void GotoMatcher::sky_direction(float& az_deg, float& el_deg) {
  if (el_deg > 90.0f) {
    az_deg += 180.0f;
    el_deg = 180.0f - el_deg;
  }
  az_deg = wrap_360(az_deg);
}

bool GotoMatcher::load(int candidate, const tracking::TleCatalog* catalog,
                       tracking::SkyTarget& target) {
  const int stored = catalog != nullptr ? static_cast<int>(catalog->size()) : 0;
  if (candidate < 0 || candidate >= stored + 2) return false;
  if (candidate >= stored) {
    target.set_body(candidate == stored ? tracking::Body::kSun : tracking::Body::kMoon);
    return true;
  }
  tracking::Tle tle;
  if (!tracking::TleCatalog::elements(catalog->entry(static_cast<std::size_t>(candidate)), tle))
    return false;
  return target.set_satellite(tle) == tracking::Sgp4Error::kOk;
}

bool GotoMatcher::near(tracking::SkyTarget& target, float az_deg, float el_deg, std::int64_t utc_ms,
                       const tracking::Observer& observer, const Pointing* before, bool* in_step) {
  tracking::LookAngles look;
  if (target.look(utc_ms, observer, look) != tracking::Sgp4Error::kOk) return false;
  // The object's recent path as a straight segment through where it is now
  // along its motion (one evaluation: the look angles carry their rates).
  const float az = static_cast<float>(look.az_deg) * kDeg2Rad;
  const float el = static_cast<float>(look.el_deg) * kDeg2Rad;
  const float az_dot = static_cast<float>(look.az_rate_deg_s) * kDeg2Rad;
  const float el_dot = static_cast<float>(look.el_rate_deg_s) * kDeg2Rad;
  const Vec3 p = unit(static_cast<float>(look.az_deg), static_cast<float>(look.el_deg));
  const Vec3 v = {-std::sin(el) * el_dot * std::sin(az) + std::cos(el) * std::cos(az) * az_dot,
                  -std::sin(el) * el_dot * std::cos(az) - std::cos(el) * std::sin(az) * az_dot,
                  std::cos(el) * el_dot};
  const float speed_deg_s = std::sqrt(dot(v, v)) / kDeg2Rad;
  float back_s = kLookBackS;
  if (speed_deg_s * back_s > kLookBackMaxDeg) back_s = kLookBackMaxDeg / speed_deg_s;
  float ahead_s = kLookAheadS;
  if (speed_deg_s * ahead_s > kToleranceDeg) ahead_s = kToleranceDeg / speed_deg_s;
  const Vec3 a = along(p, v, -back_s);
  const Vec3 b = along(p, v, ahead_s);
  const Vec3 q = unit(az_deg, el_deg);
  const Vec3 ab = sub(b, a);
  const float ab2 = dot(ab, ab);
  float s = ab2 > 0.0f ? dot(sub(q, a), ab) / ab2 : 0.0f;
  s = s < 0.0f ? 0.0f : (s > 1.0f ? 1.0f : s);
  const Vec3 d = sub(q, along(a, ab, s));
  if (chord_to_deg(std::sqrt(dot(d, d))) > kToleranceDeg) return false;
  if (in_step != nullptr) {
    // The step from the earlier go-to against the object's motion over the
    // same time (along its path as above: short steps only; chords in
    // radians, near enough degrees * kDeg2Rad at these sizes).
    const float dt_s = static_cast<float>(utc_ms - before->utc_ms) / 1000.0f;
    const Vec3 motion = along({0.0f, 0.0f, 0.0f}, v, dt_s);
    const float moved = std::sqrt(dot(motion, motion));
    const Vec3 off = sub(sub(q, unit(before->az_deg, before->el_deg)), motion);
    *in_step = moved >= kInStepMinDeg * kDeg2Rad && moved <= kLookBackMaxDeg * kDeg2Rad &&
               std::sqrt(dot(off, off)) <= kInStepToleranceDeg * kDeg2Rad + kInStepOfMotion * moved;
  }
  return true;
}

bool GotoMatcher::catalog_changed(const tracking::TleCatalog* catalog) const {
  const int stored = catalog != nullptr ? static_cast<int>(catalog->size()) : 0;
  if (stored + 2 != count_) return true;
  for (int n = 0; n < stored; ++n)
    if (catalog->entry(static_cast<std::size_t>(n)).catalog != catalog_ids_[n]) return true;
  return false;
}

void GotoMatcher::start(const tracking::TleCatalog* catalog) {
  const int stored = catalog != nullptr ? static_cast<int>(catalog->size()) : 0;
  count_ = stored + 2;
  for (int n = 0; n < stored; ++n)
    catalog_ids_[n] = catalog->entry(static_cast<std::size_t>(n)).catalog;
  for (int n = 0; n < count_; ++n) hits_[n] = kUnchecked;
  hit_last_ = 0;
  cursor_ = 0;
  started_ = true;
}

GotoMatcher::Verdict GotoMatcher::consider(float az_deg, float el_deg, std::int64_t utc_ms,
                                           const tracking::Observer& observer,
                                           const tracking::TleCatalog* catalog, int budget) {
  if (!started_ || catalog_changed(catalog)) start(catalog);
  bool any_in = false;
  for (int n = 0; n < count_; ++n) any_in = any_in || hits_[n] != kOut;
  // Every candidate missed: what the stream follows may rise later, or the
  // stream may turn to another object; compare afresh.
  if (!any_in) start(catalog);
  bool any_unchecked = false;
  for (int n = 0; n < count_; ++n) any_unchecked = any_unchecked || hits_[n] == kUnchecked;
  // The sweep gets one evaluation of every go-to while it lasts, so a small
  // budget is not spent on the candidates still in alone.
  const int in_budget = any_unchecked ? budget - 1 : budget;
  const Pointing here = {az_deg, el_deg, utc_ms};
  const std::uint32_t hit_before = hit_last_;
  hit_last_ = 0;
  Verdict v;
  // First the candidates still in: each must match this go-to to stay in;
  // one that matched the last go-to too and stepped with it is recognised
  // now (kInStep...).
  for (int n = 0; n < count_ && v.evaluated < in_budget; ++n) {
    if (hits_[n] == kOut || hits_[n] == kUnchecked) continue;
    ++v.evaluated;
    bool in_step = false;
    const bool was_hit = (hit_before >> n) & 1u;
    const bool hit = load(n, catalog, scratch_) && near(scratch_, az_deg, el_deg, utc_ms, observer,
                                                        &last_, was_hit ? &in_step : nullptr);
    int hits = hits_[n] + 1;
    if (in_step && hits < kMinHits) hits = kMinHits;
    hits_[n] = hit ? static_cast<std::uint8_t>(hits < 100 ? hits : 100) : kOut;
    if (hit) hit_last_ |= 1u << n;
  }
  // Then the sweep of those not yet compared, as far as the budget goes.
  const int from = cursor_;
  for (int k = 0; k < count_ && v.evaluated < (budget > 0 ? budget : 1); ++k) {
    const int n = (from + k) % count_;
    if (hits_[n] != kUnchecked) continue;
    ++v.evaluated;
    const bool hit = load(n, catalog, scratch_) && near(scratch_, az_deg, el_deg, utc_ms, observer);
    hits_[n] = hit ? 1 : kOut;
    if (hit) hit_last_ |= 1u << n;
    cursor_ = (n + 1) % count_;
  }
  last_ = here;
  int in = 0;
  bool unchecked = false;
  for (int n = 0; n < count_; ++n) {
    if (hits_[n] == kUnchecked) {
      unchecked = true;
    } else if (hits_[n] != kOut) {
      ++in;
      if (v.candidate < 0 || hits_[n] > hits_[v.candidate]) v.candidate = n;
    }
  }
  v.ambiguous = in > 1;
  v.recognised = !unchecked && in == 1 && hits_[v.candidate] >= kMinHits;
  return v;
}

}  // namespace rotord
