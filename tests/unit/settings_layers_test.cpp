// The stored settings are the user's layer over the defaults of the platform
// in use (issue 10 item 7): switching the base (a simulator profile) keeps
// the new base's values and the user's own changes; version-1 files that
// hold every setting are migrated without losing a value.
#include "settings/settings_layers.hpp"

#include <gtest/gtest.h>

#include <string>

#include "json/settings_json.hpp"
#include "memory_storage.hpp"
#include "string_sink.hpp"
#include "web/web_api.hpp"

namespace rotord {
namespace {

using rotord::testing::MemoryStorage;
using settings::Id;
using settings::Settings;

/// Two platform bases, as two simulator profiles set them: 0..450 with
/// elevation, and 0..360 without.
Settings g5500_like() {
  Settings s;
  s.set(Id::kAzMaxDeg, 450);
  s.set(Id::kElEnabled, 1);
  return s;
}
Settings ham4_like() {
  Settings s;
  s.set(Id::kAzMaxDeg, 360);
  s.set(Id::kElEnabled, 0);
  return s;
}

/// Every setting as it is in force, the way GET /api/settings exports it
/// and the way version-1 files were stored.
std::string whole_document(const Settings& values) {
  rotord::testing::StringSink sink;
  {
    web::JsonWriter w(sink);
    web::write_settings(values, w, web::Secrets::kReveal);
  }
  return sink.data;
}

struct Loaded {
  web::LoadOutcome outcome;
  Settings values;
};

Loaded load(MemoryStorage& storage, const Settings& base, web::LegacyBaseGuess* guess = nullptr) {
  Loaded r;
  Settings scratch;
  char buf[web::Api::kMaxDocumentBytes];
  r.outcome = web::load_settings(storage, base, guess, r.values, scratch, buf, sizeof buf);
  return r;
}

void save(MemoryStorage& storage, const Settings& values, const Settings& base) {
  char buf[web::Api::kMaxDocumentBytes];
  ASSERT_TRUE(web::save_settings(storage, values, base, buf, sizeof buf));
}

TEST(SettingsLayers, TheFileKeepsOnlyTheUsersChangesAndTheVersion) {
  const Settings base = ham4_like();
  Settings values = base;
  values.set(Id::kParkAzDeg, 123);
  MemoryStorage storage;
  save(storage, values, base);
  EXPECT_EQ(storage.document, "{\n  \"settings_version\": 2,\n  \"park.az_deg\": 123\n}\n");
}

TEST(SettingsLayers, ASwitchedBaseKeepsItsOwnGeometryAndTheUsersChanges) {
  // Saved under one profile...
  Settings values = ham4_like();
  values.set(Id::kParkAzDeg, 123);
  MemoryStorage storage;
  save(storage, values, ham4_like());
  // ...read under the other: that profile's range and elevation, the user's park.
  const Loaded r = load(storage, g5500_like());
  ASSERT_EQ(r.outcome.status, web::LoadOutcome::kLoaded) << r.outcome.reason;
  EXPECT_FALSE(r.outcome.migrated);
  EXPECT_EQ(r.values.get(Id::kAzMaxDeg), 450.0);
  EXPECT_TRUE(r.values.b(Id::kElEnabled));
  EXPECT_EQ(r.values.get(Id::kParkAzDeg), 123.0);
}

TEST(SettingsLayers, AGeometryValueTheUserSetWinsOverEveryProfile) {
  Settings values = g5500_like();
  values.set(Id::kAzMaxDeg, 400);
  MemoryStorage storage;
  save(storage, values, g5500_like());
  EXPECT_EQ(load(storage, ham4_like()).values.get(Id::kAzMaxDeg), 400.0);
  EXPECT_EQ(load(storage, g5500_like()).values.get(Id::kAzMaxDeg), 400.0);
}

TEST(SettingsLayers, AUserValueThatClashesWithTheNewBaseIsDropped) {
  Settings base = g5500_like();
  Settings values = base;
  ASSERT_EQ(values.set(Id::kAzMinDeg, 360).error, Error::kOk);  // 360..450 is a range
  MemoryStorage storage;
  save(storage, values, base);
  const Loaded r = load(storage, ham4_like());  // 360..360 is not
  EXPECT_EQ(r.outcome.status, web::LoadOutcome::kRepaired);
  EXPECT_STREQ(r.outcome.key, "az.min_deg");
  EXPECT_EQ(r.values.get(Id::kAzMaxDeg), 360.0);
  EXPECT_EQ(r.values.get(Id::kAzMinDeg), Settings().get(Id::kAzMinDeg));
}

TEST(SettingsLayers, AnExportedDocumentImportedBackChangesNothing) {
  const Settings base = g5500_like();
  Settings values = base;
  values.set(Id::kParkAzDeg, 77);
  MemoryStorage storage;
  save(storage, values, base);
  const std::string stored = storage.document;

  Settings scratch;
  web::SettingErrors errors;
  const web::ApplyOutcome r =
      web::apply_settings_json(whole_document(values), values, scratch, errors);
  ASSERT_EQ(r.status, web::ApplyOutcome::kApplied) << r.message;
  EXPECT_TRUE(r.changed.none());
  save(storage, values, base);
  EXPECT_EQ(storage.document, stored);
}

TEST(SettingsLayers, AStoredFileCanBeImportedWithItsVersionKey) {
  Settings values;
  Settings scratch;
  web::SettingErrors errors;
  const web::ApplyOutcome r = web::apply_settings_json(
      R"({"settings_version": 2, "park.az_deg": 12})", values, scratch, errors);
  ASSERT_EQ(r.status, web::ApplyOutcome::kApplied) << r.message;
  EXPECT_EQ(r.version, 2);
  EXPECT_EQ(values.get(Id::kParkAzDeg), 12.0);
}

TEST(SettingsLayers, AFileFromANewerRotordIsRefusedAndKept) {
  for (const char* doc :
       {R"({"settings_version": 3, "park.az_deg": 12})", R"({"settings_version": "two"})",
        R"({"settings_version": 1.5})", R"({"settings_version": 1e300})"}) {
    MemoryStorage storage;
    storage.document = doc;
    storage.has_document = true;
    const Loaded r = load(storage, g5500_like());
    EXPECT_EQ(r.outcome.status, web::LoadOutcome::kCorrupt) << doc;
    EXPECT_STREQ(r.outcome.key, "settings_version") << doc;
    EXPECT_EQ(r.values.get(Id::kAzMaxDeg), 450.0) << doc;
    EXPECT_EQ(storage.saves, 0);
  }
}

/// The base a version-1 file was written over, as the Linux simulator finds it.
class FixedGuess final : public web::LegacyBaseGuess {
 public:
  explicit FixedGuess(Settings base) : base_(base) {}
  const Settings& base_of(const Settings& /*file_values*/) override { return base_; }

 private:
  Settings base_;
};

TEST(SettingsLayers, AVersionOneFileBecomesTheUsersChangesOverTheBaseItWasSavedOver) {
  // Written under the ham4-like profile, every setting in it.
  Settings old = ham4_like();
  old.set(Id::kParkAzDeg, 200);
  old.set(Id::kAzOffsetDeg, -3.5);
  MemoryStorage storage;
  storage.document = whole_document(old);
  storage.has_document = true;

  FixedGuess written_under(ham4_like());
  const Loaded r = load(storage, g5500_like(), &written_under);
  ASSERT_EQ(r.outcome.status, web::LoadOutcome::kLoaded) << r.outcome.reason;
  EXPECT_TRUE(r.outcome.migrated);
  EXPECT_EQ(r.values.get(Id::kAzMaxDeg), 450.0);  // the profile in use
  EXPECT_TRUE(r.values.b(Id::kElEnabled));
  EXPECT_EQ(r.values.get(Id::kParkAzDeg), 200.0);  // the user's
  EXPECT_EQ(r.values.get(Id::kAzOffsetDeg), -3.5);

  // The next save keeps only the user's changes.
  save(storage, r.values, g5500_like());
  EXPECT_EQ(storage.document,
            "{\n  \"settings_version\": 2,\n  \"park.az_deg\": 200,\n  \"az.offset_deg\": "
            "-3.5\n}\n");
}

TEST(SettingsLayers, AVersionOneFileWithoutAGuessKeepsEveryValueItChanged) {
  Settings old;  // the Pico W's or --hw gpiod's: the base is the same before and after
  old.set(Id::kAzMaxDeg, 400);
  old.set(Id::kParkAzDeg, 10);
  MemoryStorage storage;
  storage.document = whole_document(old);
  storage.has_document = true;
  const Loaded r = load(storage, Settings());
  ASSERT_EQ(r.outcome.status, web::LoadOutcome::kLoaded);
  EXPECT_TRUE(r.outcome.migrated);
  for (std::size_t n = 0; n < settings::kCount; ++n)
    EXPECT_TRUE(r.values.same_value(static_cast<Id>(n), old))
        << settings::def(static_cast<Id>(n)).key;
}

TEST(SettingsLayers, AHandWrittenPartialFileIsTheUsersLayer) {
  // No version key and only some keys: a file a user wrote, read as changes.
  MemoryStorage storage;
  storage.document = R"({"park.az_deg": 33})";
  storage.has_document = true;
  FixedGuess none(Settings{});
  const Loaded r = load(storage, g5500_like(), &none);
  ASSERT_EQ(r.outcome.status, web::LoadOutcome::kLoaded);
  EXPECT_EQ(r.values.get(Id::kParkAzDeg), 33.0);
  EXPECT_EQ(r.values.get(Id::kAzMaxDeg), 450.0);
}

}  // namespace
}  // namespace rotord
