// Issue 26's portable pieces: the preset row format, the place parser the
// console and MQTT share, and where the beam points after a flip.
#include <gtest/gtest.h>

#include <string>

#include "rotator/place.hpp"
#include "settings/preset.hpp"

namespace rotord {
namespace {

using settings::Preset;

TEST(Presets, RowsParseAndFormatBothWays) {
  Preset p;
  ASSERT_EQ(settings::parse_preset("150L:JA LP", p), nullptr);
  EXPECT_DOUBLE_EQ(p.az_deg, 150.0);
  EXPECT_TRUE(p.long_path);
  EXPECT_STREQ(p.name, "JA LP");
  char row[32];
  EXPECT_EQ(std::string(row, settings::format_preset(p, row, sizeof row)), "150.0L:JA LP");
  ASSERT_EQ(settings::parse_preset("45:EU:west", p), nullptr);  // the name may hold a colon
  EXPECT_STREQ(p.name, "EU:west");
  EXPECT_FALSE(p.long_path);
}

TEST(Presets, BadRowsAndNamesSayWhy) {
  Preset p;
  EXPECT_STREQ(settings::parse_preset("EU", p), "not <az_deg>[L]:<name> (e.g. 45:EU or 150L:JA)");
  EXPECT_STREQ(settings::parse_preset("360:EU", p), "the heading is outside 0..360");
  EXPECT_STREQ(settings::parse_preset("4x5:EU", p), "the heading is not a number of degrees");
  EXPECT_STREQ(settings::parse_preset("45:", p), "a preset needs a name");
  EXPECT_STREQ(settings::check_preset_name(std::string(21, 'n')),
               "a preset name is at most 20 bytes");
  EXPECT_NE(settings::check_preset_name("say \"hi\""), nullptr);
  EXPECT_NE(settings::check_preset_name(" EU"), nullptr);
  // The settings table checks a preset row with the same parser.
  settings::Settings s;
  EXPECT_EQ(s.set_text(settings::preset_id(0), "45:EU").error, Error::kOk);
  EXPECT_EQ(s.set_text(settings::preset_id(1), "400:X").error, Error::kInvalidArgument);
  EXPECT_EQ(settings::find_preset(s, "eu"), std::optional<std::size_t>(0));
}

TEST(Places, TheConsolesLineTakesALocatorOrAPositionAndAPath) {
  PlaceQuery q;
  ASSERT_EQ(parse_place("jo62qm", q), nullptr);
  EXPECT_STREQ(q.locator, "JO62QM");
  EXPECT_NEAR(q.to.lat_deg, 52.5208, 1e-3);
  EXPECT_EQ(q.path, tracking::Path::kShort);
  ASSERT_EQ(parse_place("-33.87, 151.21 long", q), nullptr);
  EXPECT_DOUBLE_EQ(q.to.lat_deg, -33.87);
  EXPECT_DOUBLE_EQ(q.to.lon_deg, 151.21);
  EXPECT_EQ(q.path, tracking::Path::kLong);
  EXPECT_EQ(q.locator[0], '\0');
  EXPECT_STREQ(parse_place("JO6", q), "a locator has 4, 6, 8 or 10 characters (e.g. JO62QM)");
  EXPECT_STREQ(parse_place("JO62 sideways", q), "the path is short or long");
  EXPECT_STREQ(parse_place("10 200", q), "longitude is outside -180..180");
  EXPECT_STREQ(parse_place("10 x", q), "a position is <lat> <lon> in degrees");
  EXPECT_STREQ(parse_place("", q),
               "give a locator or a latitude and longitude, then short or long");
}

TEST(Beam, AFlipOverTheZenithTurnsTheBeamRound) {
  Beam b = beam_of(370.0, 30.0, true);
  EXPECT_DOUBLE_EQ(b.az_deg, 10.0);
  EXPECT_DOUBLE_EQ(b.el_deg, 30.0);
  b = beam_of(100.0, 150.0, true);  // flipped: the beam looks the other way
  EXPECT_DOUBLE_EQ(b.az_deg, 280.0);
  EXPECT_DOUBLE_EQ(b.el_deg, 30.0);
  b = beam_of(-20.0, 0.0, false);
  EXPECT_DOUBLE_EQ(b.az_deg, 340.0);
}

}  // namespace
}  // namespace rotord
