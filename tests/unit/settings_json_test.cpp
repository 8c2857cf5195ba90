// The settings document: round trip, all-or-nothing application, and loading
// from storage (a corrupt or invalid document leaves the defaults alone).
#include "json/settings_json.hpp"

#include <gtest/gtest.h>

#include <string>

#include "http_test_client.hpp"
#include "memory_storage.hpp"
#include "settings_bases.hpp"
#include "web/http_request.hpp"
#include "web/web_api.hpp"

namespace rotord::web {
namespace {

using rotord::testing::MemoryStorage;
using settings::Id;

std::string encode(const settings::Settings& s) {
  rotord::testing::StringSink sink;
  {
    JsonWriter w(sink);
    write_settings(s, w);
  }
  return sink.data;
}

TEST(SettingsJson, RoundTripsEveryType) {
  settings::Settings a;
  a.set(Id::kAzOffsetDeg, -12.25);
  a.set(Id::kAzCoastS, 0.15);
  a.set(Id::kAzDrive, 3);
  a.set(Id::kElEnabled, 1);
  a.set(Id::kAzMinDeg, -180);
  a.set(Id::kAzMaxDeg, 540);
  a.set(Id::kNetMaxClients, 3);
  const std::string doc = encode(a);
  EXPECT_NE(doc.find(R"("az.drive":"hbridge")"), std::string::npos) << doc;
  EXPECT_NE(doc.find(R"("az.coast_s":0.15,)"), std::string::npos) << doc;
  settings::Settings b;
  settings::Settings scratch;
  SettingErrors errors;
  const ApplyOutcome r = apply_settings_json(doc, b, scratch, errors);
  ASSERT_EQ(r.status, ApplyOutcome::kApplied) << r.message;
  for (std::size_t n = 0; n < settings::kCount; ++n)
    EXPECT_EQ(a.get(static_cast<Id>(n)), b.get(static_cast<Id>(n)))
        << settings::def(static_cast<Id>(n)).key;
  EXPECT_EQ(encode(b), doc);
}

TEST(SettingsJson, TheWholeDocumentFitsTheRequestBodyWithRoomToGrow) {
  const std::string doc = encode(settings::Settings());
  EXPECT_LT(doc.size() * 4 / 3, HttpRequestParser::kMaxBodyBytes) << doc.size();
  // The pretty stored form fits the storage buffer with the same margin,
  // even when the user changed every setting.
  MemoryStorage storage;
  char buf[Api::kMaxDocumentBytes];
  const settings::Settings values;
  ASSERT_TRUE(save_settings(storage, values, rotord::testing::differs_everywhere(values), buf,
                            sizeof(buf)));
  EXPECT_GT(storage.document.size(), doc.size());
  EXPECT_LT(storage.document.size() * 4 / 3, sizeof(buf)) << storage.document.size();
}

TEST(SettingsJson, PartialDocumentsChangeOnlyTheirKeys) {
  settings::Settings s;
  settings::Settings scratch;
  SettingErrors errors;
  const ApplyOutcome r =
      apply_settings_json(R"({"park.az_deg": 90, "az.has_brake": true})", s, scratch, errors);
  ASSERT_EQ(r.status, ApplyOutcome::kApplied);
  EXPECT_EQ(r.changed.count(), 2u);
  EXPECT_TRUE(r.changed.test(static_cast<std::size_t>(Id::kParkAzDeg)));
  EXPECT_EQ(s.get(Id::kParkAzDeg), 90.0);
  EXPECT_TRUE(s.b(Id::kAzHasBrake));
  EXPECT_EQ(s.get(Id::kAzMaxDeg), settings::def(Id::kAzMaxDeg).default_value);
}

TEST(SettingsJson, AllOrNothingWithAReasonPerKey) {
  settings::Settings s;
  const settings::Settings before = s;
  settings::Settings scratch;
  SettingErrors errors;
  const ApplyOutcome r = apply_settings_json(
      R"({"park.az_deg": 90, "az.stall_ms": 1.5, "az.sensor": 1, "az.continuous": "yes",)"
      R"( "az.tolerance_deg": {"x":1}, "park.az_deg": 91})",
      s, scratch, errors);
  EXPECT_EQ(r.status, ApplyOutcome::kInvalid);
  ASSERT_EQ(errors.size(), 5u);
  EXPECT_STREQ(errors[0].key, "az.stall_ms");
  EXPECT_STREQ(errors[0].reason, "must be a whole number");
  EXPECT_STREQ(errors[1].key, "az.sensor");
  EXPECT_STREQ(errors[2].key, "az.continuous");
  EXPECT_STREQ(errors[3].reason, "expected a number");
  EXPECT_STREQ(errors[4].reason, "given twice");
  for (std::size_t n = 0; n < settings::kCount; ++n)
    EXPECT_EQ(s.get(static_cast<Id>(n)), before.get(static_cast<Id>(n)));
  EXPECT_EQ(s.revision(), before.revision());
}

TEST(SettingsJson, ManyErrorsAreCountedBeyondTheTable) {
  std::string doc = "{";
  for (int n = 0; n < 20; ++n)
    doc += (n ? "," : "") + std::string("\"bad") + std::to_string(n) + "\":1";
  doc += "}";
  settings::Settings s;
  settings::Settings scratch;
  SettingErrors errors;
  EXPECT_EQ(apply_settings_json(doc, s, scratch, errors).status, ApplyOutcome::kInvalid);
  EXPECT_EQ(errors.size(), SettingErrors::kMax);
  EXPECT_EQ(errors.dropped(), 20u - SettingErrors::kMax);
}

TEST(SettingsJson, LoadNothingStoredKeepsTheDefaults) {
  MemoryStorage storage;
  settings::Settings s;
  settings::Settings scratch;
  char buf[256];
  EXPECT_EQ(
      load_settings(storage, settings::Settings(), nullptr, s, scratch, buf, sizeof(buf)).status,
      LoadOutcome::kNothingStored);
}

TEST(SettingsJson, LoadAppliesAValidDocument) {
  MemoryStorage storage;
  storage.has_document = true;
  storage.document = "{\n  \"az.offset_deg\": 4.5\n}\n";
  settings::Settings s;
  settings::Settings scratch;
  char buf[256];
  EXPECT_EQ(
      load_settings(storage, settings::Settings(), nullptr, s, scratch, buf, sizeof(buf)).status,
      LoadOutcome::kLoaded);
  EXPECT_EQ(s.get(Id::kAzOffsetDeg), 4.5);
}

TEST(SettingsJson, UnreadableDocumentsLeaveTheDefaultsFailClosedAndAreNotRewritten) {
  for (const char* doc : {"{\"az.offset_deg\": 4.5", "\x00\x00\x00", "[1, 2]"}) {
    MemoryStorage storage;
    storage.has_document = true;
    storage.document = doc;
    settings::Settings s;
    const settings::Settings before = s;
    settings::Settings scratch;
    char buf[256];
    LoadReport report;
    const LoadOutcome r = load_settings(storage, settings::Settings(), nullptr, s, scratch, buf,
                                        sizeof(buf), &report);
    EXPECT_EQ(r.status, LoadOutcome::kCorrupt) << doc;
    EXPECT_STRNE(r.reason, "") << doc;
    EXPECT_TRUE(r.access_unreadable) << doc;
    EXPECT_TRUE(s.access_unreadable()) << doc;
    EXPECT_TRUE(report.access_unreadable) << doc;
    for (std::size_t n = 0; n < settings::kCount; ++n)
      EXPECT_EQ(s.get(static_cast<Id>(n)), before.get(static_cast<Id>(n))) << doc;
    EXPECT_EQ(storage.saves, 0);
  }
}

TEST(SettingsJson, ADamagedDocumentKeepsEveryValidValueAndNamesTheBadOnes) {
  const struct {
    const char* doc;
    const char* key;  // the member named as dropped
    bool access;      // fails closed
  } cases[] = {
      {R"({"az.offset_deg": 4.5, "az.max_deg": 99999})", "az.max_deg", false},   // out of range
      {R"({"az.offset_deg": 4.5, "az.max_deg": "wide"})", "az.max_deg", false},  // wrong type
      {R"({"az.offset_deg": 4.5, "az.offset": 1})", "az.offset", false},         // unknown key
      {R"({"az.offset_deg": 4.5, "az.min_deg": 300, "az.max_deg": 200})", "az.min_deg", false},
      {R"({"az.offset_deg": 4.5, "park.az_deg": 1, "park.az_deg": 2})", "park.az_deg", false},
      // The access settings themselves: every valid value still read, but closed.
      {R"({"az.offset_deg": 4.5, "access.control_networks": "10.0.0.0/33"})",
       "access.control_networks", true},
      {R"({"az.offset_deg": 4.5, "web.password": 12})", "web.password", true},
      {R"({"az.offset_deg": 4.5, "access.control_network": "10.0.0.0/8"})",
       "access.control_network", true},  // a typo: meant as a rule
      // Cut short after a whole member: the start is read, the rest unknown.
      {"{\"az.offset_deg\": 4.5,\n \"access.control_networks\": \"10.", "", true},
  };
  for (const auto& c : cases) {
    MemoryStorage storage;
    storage.has_document = true;
    storage.document = c.doc;
    settings::Settings s;
    settings::Settings scratch;
    char buf[256];
    LoadReport report;
    const LoadOutcome r = load_settings(storage, settings::Settings(), nullptr, s, scratch, buf,
                                        sizeof(buf), &report);
    EXPECT_EQ(r.status, LoadOutcome::kRepaired) << c.doc;
    EXPECT_EQ(s.get(Id::kAzOffsetDeg), 4.5) << c.doc;  // the valid value is kept
    ASSERT_GE(report.size(), 1u) << c.doc;
    EXPECT_STREQ(report[0].key, c.key) << c.doc;
    EXPECT_STRNE(report[0].reason, "") << c.doc;
    EXPECT_EQ(r.access_unreadable, c.access) << c.doc;
    EXPECT_EQ(s.access_unreadable(), c.access) << c.doc;
    EXPECT_EQ(s.check_consistency().error, Error::kOk) << c.doc;
    EXPECT_EQ(s.get(Id::kAzMaxDeg), settings::Settings().get(Id::kAzMaxDeg)) << c.doc;
    EXPECT_TRUE(s.text(Id::kAccessControlNetworks).empty()) << c.doc;
    EXPECT_EQ(storage.saves, 0);
  }
}

TEST(SettingsJson, BothSidesOfABrokenRuleAreDroppedAndTheRestKept) {
  MemoryStorage storage;
  storage.has_document = true;
  storage.document = R"({"az.min_deg": 300, "az.max_deg": 200, "park.el_deg": 12})";
  settings::Settings s;
  settings::Settings scratch;
  char buf[256];
  LoadReport report;
  ASSERT_EQ(
      load_settings(storage, settings::Settings(), nullptr, s, scratch, buf, sizeof(buf), &report)
          .status,
      LoadOutcome::kRepaired);
  EXPECT_EQ(report.size(), 2u);
  EXPECT_EQ(s.get(Id::kParkElDeg), 12.0);
  EXPECT_EQ(s.get(Id::kAzMinDeg), settings::Settings().get(Id::kAzMinDeg));
  EXPECT_FALSE(s.access_unreadable());
}

TEST(SettingsJson, LoadReportsADocumentTooLargeForTheBuffer) {
  MemoryStorage storage;
  storage.has_document = true;
  storage.document = std::string(300, ' ') + "{}";
  settings::Settings s;
  settings::Settings scratch;
  char buf[256];
  EXPECT_EQ(
      load_settings(storage, settings::Settings(), nullptr, s, scratch, buf, sizeof(buf)).status,
      LoadOutcome::kCorrupt);
}

TEST(SettingsJson, SaveWritesAPrettyDocumentThatLoadsBack) {
  MemoryStorage storage;
  settings::Settings s;
  s.set(Id::kParkElDeg, 45);
  char buf[Api::kMaxDocumentBytes];
  ASSERT_TRUE(save_settings(storage, s, settings::Settings(), buf, sizeof(buf)));
  // Only the user's layer, after the version.
  EXPECT_EQ(storage.document, "{\n  \"settings_version\": 2,\n  \"park.el_deg\": 45\n}\n");
  EXPECT_EQ(storage.document.back(), '\n');
  settings::Settings t;
  settings::Settings scratch;
  ASSERT_EQ(
      load_settings(storage, settings::Settings(), nullptr, t, scratch, buf, sizeof(buf)).status,
      LoadOutcome::kLoaded);
  EXPECT_EQ(t.get(Id::kParkElDeg), 45.0);
  char small[32];
  EXPECT_FALSE(save_settings(storage, s, settings::Settings(), small,
                             sizeof(small)));  // does not fit: not saved
  EXPECT_EQ(storage.saves, 1);
}

}  // namespace
}  // namespace rotord::web
