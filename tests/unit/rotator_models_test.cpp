// The rotator model list (core/settings/rotator_models.*): every known
// figure is a value its setting accepts, applying a model fills exactly its
// known figures, and nothing changes when one is refused.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "settings/rotator_models.hpp"

namespace rotord::settings {
namespace {

TEST(RotatorModels, TheIssueModelsAreListedOnceEach) {
  std::set<std::string> ids;
  for (const RotatorModel& m : rotator_models()) {
    EXPECT_TRUE(ids.insert(m.id).second) << m.id;
    EXPECT_NE(std::string(m.name), "");
    EXPECT_NE(std::string(m.note), "");
  }
  for (const char* id :
       {"yaesu-g5500", "yaesu-g5500dc", "yaesu-g450", "yaesu-g650", "yaesu-g1000dxa",
        "yaesu-g2800dxa", "hygain-ham4", "hygain-t2x", "hygain-cd45", "spid-ras", "spid-big-ras",
        "alfa-spx", "prosistel-d", "create-rc5", "other"})
    EXPECT_EQ(ids.count(id), 1u) << id;
  EXPECT_EQ(find_rotator_model("no-such-rotator"), nullptr);
}

TEST(RotatorModels, EveryKnownFigureHasASourceAndIsAValidValue) {
  for (const RotatorModel& m : rotator_models()) {
    ModelSetting rows[kModelSettingCount];
    const std::size_t n = model_settings(m, rows, kModelSettingCount);
    for (std::size_t k = 0; k < n; ++k) {
      if (!rows[k].figure->known()) continue;
      EXPECT_EQ(rows[k].figure->source[0], '[') << m.id << " " << def(rows[k].id).key;
      EXPECT_EQ(validate(rows[k].id, rows[k].figure->value).error, Error::kOk)
          << m.id << " " << def(rows[k].id).key;
    }
    Settings s;
    EXPECT_EQ(apply_rotator_model(m, s).error, Error::kOk) << m.id;
  }
}

TEST(RotatorModels, ApplyingAModelFillsItsKnownFiguresOnly) {
  Settings s;
  ASSERT_EQ(s.set(Id::kAzSpeedDegS, 3.5).error, Error::kOk);
  ASSERT_EQ(s.set(Id::kAzBrakeEngageMs, 4000).error, Error::kOk);
  ASSERT_EQ(apply_rotator_model(*find_rotator_model("hygain-ham4"), s).error, Error::kOk);
  EXPECT_EQ(s.get(Id::kAzMaxDeg), 360.0);
  EXPECT_EQ(s.get(Id::kAzMinDeg), 0.0);
  EXPECT_TRUE(s.b(Id::kAzHasBrake));
  EXPECT_FALSE(s.b(Id::kElEnabled));
  // No published speed or brake delay: the owner's values stay.
  EXPECT_EQ(s.get(Id::kAzSpeedDegS), 3.5);
  EXPECT_EQ(s.get(Id::kAzBrakeEngageMs), 4000.0);

  ASSERT_EQ(apply_rotator_model(*find_rotator_model("spid-ras"), s).error, Error::kOk);
  EXPECT_EQ(s.get(Id::kAzMinDeg), -180.0);
  EXPECT_EQ(s.get(Id::kAzMaxDeg), 540.0);
  EXPECT_EQ(s.i(Id::kAzDrive), 3);
  EXPECT_EQ(s.i(Id::kElDrive), 3);
  EXPECT_TRUE(s.b(Id::kElEnabled));
  EXPECT_EQ(s.get(Id::kAzSpeedDegS), 6.0);

  const Settings before = s;
  ASSERT_EQ(apply_rotator_model(*find_rotator_model("other"), s).error, Error::kOk);
  for (std::size_t id = 0; id < kCount; ++id)
    EXPECT_TRUE(s.same_value(static_cast<Id>(id), before)) << def(static_cast<Id>(id)).key;
}

TEST(RotatorModels, ARefusedModelChangesNothingAndSaysWhy) {
  // A row that knows only where the travel starts (a future model), on
  // settings whose travel ends below that: refused as a whole, with the rule.
  RotatorModel partial{"test", "Test", {3, "[T]"}, {}, {300, "[T]"}, {}, {}, {},
                       {},     {},     {},         {}, {},           {}, {}, "test row"};
  Settings s;
  ASSERT_EQ(s.set(Id::kAzMaxDeg, 200).error, Error::kOk);
  const Settings before = s;
  const Rejection r = apply_rotator_model(partial, s);
  EXPECT_EQ(r.error, Error::kOutOfRange);
  EXPECT_STREQ(r.reason, "az.min_deg must be below az.max_deg");
  for (std::size_t id = 0; id < kCount; ++id)
    EXPECT_TRUE(s.same_value(static_cast<Id>(id), before)) << def(static_cast<Id>(id)).key;
}

}  // namespace
}  // namespace rotord::settings
