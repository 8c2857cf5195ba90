// The rules checked when values are saved (Settings::check_dependent,
// issue 23 item 5): park within the travel, slow zones shorter than it, each
// message naming both settings; judged by what a save changes.
#include <gtest/gtest.h>

#include <string>

#include "json/settings_json.hpp"
#include "settings/settings.hpp"

namespace rotord::settings {
namespace {

TEST(SettingsDependent, DefaultsPass) {
  Settings s;
  const Settings before;
  s.set(Id::kParkAzDeg, 10);
  EXPECT_EQ(s.check_dependent(before).error, Error::kOk);
}

TEST(SettingsDependent, ParkOutsideTheTravelIsRefusedNamingBoth) {
  Settings s;  // az 0..450 by default
  const Rejection r = s.save_from_text(Id::kParkAzDeg, "500");
  EXPECT_EQ(r.error, Error::kOutOfRange);
  EXPECT_EQ(std::string(r.reason),
            "park.az_deg 500 is outside the azimuth travel az.min_deg..az.max_deg (0..450): PARK "
            "could not go there");
  EXPECT_EQ(s.get(Id::kParkAzDeg), 0.0);  // undone
  // Shrinking the travel below the park position is refused the same way.
  ASSERT_EQ(s.save_from_text(Id::kParkAzDeg, "400").error, Error::kOk);
  EXPECT_NE(std::string(s.save_from_text(Id::kAzMaxDeg, "360").reason).find("park.az_deg 400"),
            std::string::npos);
  EXPECT_EQ(s.get(Id::kAzMaxDeg), 450.0);
  // A continuous azimuth takes any bearing.
  ASSERT_EQ(s.save_from_text(Id::kAzContinuous, "true").error, Error::kOk);
  EXPECT_EQ(s.save_from_text(Id::kParkAzDeg, "700").error, Error::kOk);
}

TEST(SettingsDependent, ParkElevationAndSlowZonesWithinTheirTravel) {
  Settings s;
  ASSERT_EQ(s.set(Id::kElEnabled, 1).error, Error::kOk);
  ASSERT_EQ(s.set(Id::kElMaxDeg, 90).error, Error::kOk);
  EXPECT_NE(std::string(s.save_from_text(Id::kParkElDeg, "120").reason).find("el.max_deg"),
            std::string::npos);
  ASSERT_EQ(s.set(Id::kAzMaxDeg, 60).error, Error::kOk);
  const Rejection r = s.save_from_text(Id::kAzSlowZoneDeg, "80");
  EXPECT_EQ(r.error, Error::kOutOfRange);
  EXPECT_NE(std::string(r.reason).find("az.slow_zone_deg 80"), std::string::npos);
  EXPECT_NE(std::string(r.reason).find("az.max_deg"), std::string::npos);
  ASSERT_EQ(s.set(Id::kElMaxDeg, 4).error, Error::kOk);
  EXPECT_NE(std::string(s.save_from_text(Id::kElSlowZoneDeg, "5").reason).find("el.slow_zone_deg"),
            std::string::npos);
}

// The whole wording of each travel rule: the park, the wind stow and the
// slow zones share one sentence per kind (settings_dependent.cpp), which
// must read for each setting exactly as it did when each had its own.
TEST(SettingsDependent, EachTravelRuleNamesItsSettingsAxisAndValues) {
  Settings s;
  ASSERT_EQ(s.set(Id::kElEnabled, 1).error, Error::kOk);
  ASSERT_EQ(s.set(Id::kElMaxDeg, 90).error, Error::kOk);
  EXPECT_EQ(std::string(s.save_from_text(Id::kParkElDeg, "120").reason),
            "park.el_deg 120 is outside the elevation travel el.min_deg..el.max_deg (0..90): "
            "PARK could not go there");
  ASSERT_EQ(s.set(Id::kWindSource, 2).error, Error::kOk);
  EXPECT_EQ(std::string(s.save_from_text(Id::kWindStowAzDeg, "-10.5").reason),
            "wind.stow_az_deg -10.5 is outside the azimuth travel az.min_deg..az.max_deg "
            "(0..450): a wind stow could not go there");
  ASSERT_EQ(s.set(Id::kAzMaxDeg, 60).error, Error::kOk);
  EXPECT_EQ(std::string(s.save_from_text(Id::kAzSlowZoneDeg, "80").reason),
            "az.slow_zone_deg 80 must be shorter than the azimuth travel az.min_deg..az.max_deg "
            "(60 deg)");
  ASSERT_EQ(s.set(Id::kElMaxDeg, 4).error, Error::kOk);
  EXPECT_EQ(std::string(s.save_from_text(Id::kElSlowZoneDeg, "5").reason),
            "el.slow_zone_deg 5 must be shorter than the elevation travel el.min_deg..el.max_deg "
            "(4 deg)");
}

TEST(SettingsDependent, ASaveIsJudgedByWhatItChanges) {
  // A value already out of line (a file written before the rule) does not
  // block an unrelated save; the file loader is not held to the rules.
  Settings s;
  ASSERT_EQ(s.set(Id::kParkAzDeg, 500).error, Error::kOk);
  Settings scratch;
  web::SettingErrors errors;
  EXPECT_EQ(web::apply_settings_json(R"({"station.alt_m": 12})", s, scratch, errors, true).status,
            web::ApplyOutcome::kApplied);
  EXPECT_EQ(web::apply_settings_json(R"({"park.az_deg": 501})", s, scratch, errors, true).status,
            web::ApplyOutcome::kInvalid);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(std::string(errors[0].key), "park.az_deg");
  // Not saving (the loader): the same document is taken.
  EXPECT_EQ(web::apply_settings_json(R"({"park.az_deg": 501})", s, scratch, errors, false).status,
            web::ApplyOutcome::kApplied);
}

}  // namespace
}  // namespace rotord::settings
