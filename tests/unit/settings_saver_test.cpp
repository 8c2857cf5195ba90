// SettingsSaver on a fake hal::Storage (the hardware boundary), in virtual
// time: changes made outside the REST API are written once after a quiet
// time, unchanged documents are never written, failures are retried, and a
// change the API saved is not written again.
#include "storage/settings_saver.hpp"

#include <gtest/gtest.h>

#include <string>

#include "fake_rotator.hpp"
#include "http_test_client.hpp"
#include "json/settings_json.hpp"
#include "memory_storage.hpp"
#include "web/http_session.hpp"
#include "web/web_api.hpp"

namespace rotord {
namespace {

using rotord::testing::MemoryStorage;
using settings::Id;

const settings::Settings kTableDefaults;  // the base below the user's layer

class SaverTest : public ::testing::Test {
 protected:
  void SetUp() override { saver.begin(); }

  settings::Settings values;
  MemoryStorage storage;
  char buf[web::Api::kMaxDocumentBytes];
  SettingsSaver saver{values, kTableDefaults, storage, buf, sizeof buf};
};

TEST_F(SaverTest, NothingChangedNothingWritten) {
  for (Millis t = 0; t < 20000; t += 10) EXPECT_EQ(saver.poll(t), SettingsSaver::Result::kIdle);
  EXPECT_EQ(storage.attempts, 0);
  EXPECT_FALSE(saver.pending());
}

TEST_F(SaverTest, ABurstOfChangesIsWrittenOnceAfterTheQuietTime) {
  Millis t = 1000;
  // Five writes 500 ms apart (a client walking through CW registers).
  for (int n = 0; n < 5; ++n) {
    ASSERT_EQ(values.set(Id::kParkAzDeg, 10.0 * (n + 1)).error, Error::kOk);
    for (Millis end = t + 500; t < end; t += 10) saver.poll(t);
  }
  EXPECT_EQ(storage.attempts, 0);  // never quiet long enough yet
  EXPECT_TRUE(saver.pending());
  // Just before the quiet time since the last change ends: still waiting.
  const Millis last_change = t - 500;
  for (; t < last_change + SettingsSaver::kQuietMs - 10; t += 10)
    EXPECT_EQ(saver.poll(t), SettingsSaver::Result::kWaiting);
  EXPECT_EQ(storage.attempts, 0);
  SettingsSaver::Result r = SettingsSaver::Result::kWaiting;
  for (Millis end = t + 100; t < end && r == SettingsSaver::Result::kWaiting; t += 10)
    r = saver.poll(t);
  EXPECT_EQ(r, SettingsSaver::Result::kSaved);
  EXPECT_EQ(storage.saves, 1);
  for (Millis end = t + 20000; t < end; t += 10) saver.poll(t);
  EXPECT_EQ(storage.saves, 1);
  EXPECT_FALSE(saver.pending());

  // The stored document is the API's document, and loads back.
  settings::Settings loaded, scratch;
  char load_buf[web::Api::kMaxDocumentBytes];
  EXPECT_EQ(web::load_settings(storage, settings::Settings(), nullptr, loaded, scratch, load_buf,
                               sizeof load_buf)
                .status,
            web::LoadOutcome::kLoaded);
  EXPECT_EQ(loaded.get(Id::kParkAzDeg), 50.0);
  MemoryStorage api_storage;
  char api_buf[web::Api::kMaxDocumentBytes];
  ASSERT_TRUE(
      web::save_settings(api_storage, values, settings::Settings(), api_buf, sizeof api_buf));
  EXPECT_EQ(storage.document, api_storage.document);
}

TEST_F(SaverTest, AChangeAndItsUndoWriteNothing) {
  // What is stored is known from the start-up load.
  ASSERT_TRUE(web::save_settings(storage, values, settings::Settings(), buf, sizeof buf));
  storage.saves = storage.attempts = 0;
  settings::Settings scratch;
  char load_buf[web::Api::kMaxDocumentBytes];
  ASSERT_EQ(web::load_settings(saver, settings::Settings(), nullptr, values, scratch, load_buf,
                               sizeof load_buf)
                .status,
            web::LoadOutcome::kLoaded);
  saver.begin();

  const double before = values.get(Id::kAzOffsetDeg);
  values.set(Id::kAzOffsetDeg, before + 5.0);
  saver.poll(0);
  values.set(Id::kAzOffsetDeg, before);
  EXPECT_TRUE(saver.pending());
  SettingsSaver::Result last = SettingsSaver::Result::kIdle;
  for (Millis t = 0; t < 10000; t += 10) {
    const SettingsSaver::Result r = saver.poll(t);
    if (r != SettingsSaver::Result::kWaiting && r != SettingsSaver::Result::kIdle) last = r;
  }
  EXPECT_EQ(last, SettingsSaver::Result::kUnchanged);
  EXPECT_EQ(storage.attempts, 0);
  EXPECT_FALSE(saver.pending());
}

TEST_F(SaverTest, AFailedWriteIsRetriedLaterAndTheSettingsStay) {
  storage.fail = true;
  values.set(Id::kParkAzDeg, 123.0);
  Millis t = 0;
  int failures = 0;
  Millis first_failure = -1;
  for (; t < SettingsSaver::kQuietMs + 30000; t += 10) {
    if (saver.poll(t) == SettingsSaver::Result::kFailed) {
      if (failures++ == 0) first_failure = t;
    }
  }
  // 5 s, then 10 s, then 20 s: three attempts in the 30 s after the first.
  EXPECT_EQ(first_failure, SettingsSaver::kQuietMs);
  EXPECT_EQ(failures, 3);
  EXPECT_EQ(storage.attempts, 3);
  EXPECT_EQ(values.get(Id::kParkAzDeg), 123.0);  // still in force
  EXPECT_TRUE(saver.pending());

  storage.fail = false;  // the card is back
  SettingsSaver::Result r = SettingsSaver::Result::kWaiting;
  for (Millis end = t + SettingsSaver::kMaxRetryMs + 10; t < end; t += 10) {
    r = saver.poll(t);
    if (r == SettingsSaver::Result::kSaved) break;
  }
  EXPECT_EQ(r, SettingsSaver::Result::kSaved);
  EXPECT_EQ(storage.saves, 1);
  EXPECT_EQ(saver.retry_delay_ms(), 0);
  EXPECT_NE(storage.document.find("\"park.az_deg\": 123"), std::string::npos) << storage.document;
}

TEST_F(SaverTest, ATooLargeDocumentFailsWithoutWriting) {
  char tiny[16];
  SettingsSaver small(values, kTableDefaults, storage, tiny, sizeof tiny);
  small.begin();
  values.set(Id::kParkAzDeg, 1.0);
  EXPECT_EQ(small.flush(0), SettingsSaver::Result::kFailed);
  EXPECT_EQ(storage.attempts, 0);
}

TEST_F(SaverTest, WaitsWhileTheRotatorMovesAndFlushDoesNot) {
  values.set(Id::kParkAzDeg, 42.0);
  for (Millis t = 0; t < 10000; t += 10)
    EXPECT_NE(saver.poll(t, /*busy=*/true), SettingsSaver::Result::kSaved);
  EXPECT_EQ(storage.attempts, 0);
  EXPECT_EQ(saver.poll(10000, false), SettingsSaver::Result::kSaved);

  values.set(Id::kParkAzDeg, 43.0);
  EXPECT_EQ(saver.flush(10010), SettingsSaver::Result::kSaved);  // shutdown: no quiet time
  EXPECT_EQ(storage.saves, 2);
  EXPECT_EQ(saver.flush(10020), SettingsSaver::Result::kIdle);
}

TEST(SettingsSaverApi, AChangeTheApiSavedIsNotWrittenAgain) {
  rotord::testing::FakeRotator r;
  MemoryStorage storage;
  char buf[web::Api::kMaxDocumentBytes];
  SettingsSaver saver(r.settings, kTableDefaults, storage, buf, sizeof buf);
  saver.begin();
  web::Api api(web::ApiContext{*r.controller, &saver, nullptr, nullptr, "test"});
  web::HttpSession session(api);
  // A protocol change still waits for its quiet time when the API saves.
  r.settings.set(Id::kAzOffsetDeg, 7.0);
  saver.poll(0);
  const std::string body = R"({"park.az_deg": 33})";
  rotord::testing::StringSink sink;
  session.receive(rotord::testing::post_request("/api/settings", body), sink);
  const auto responses = rotord::testing::parse_responses(sink.data);
  ASSERT_EQ(responses.size(), 1u) << sink.data;
  EXPECT_EQ(responses[0].status, 200) << responses[0].body;
  EXPECT_EQ(storage.saves, 1);
  // The API's document holds both changes: nothing is left for the saver.
  EXPECT_NE(storage.document.find("\"az.offset_deg\": 7"), std::string::npos) << storage.document;
  EXPECT_NE(storage.document.find("\"park.az_deg\": 33"), std::string::npos) << storage.document;
  for (Millis t = 10; t < 20000; t += 10) EXPECT_EQ(saver.poll(t), SettingsSaver::Result::kIdle);
  EXPECT_EQ(storage.attempts, 1);
}

TEST(SettingsSaverApi, AFailedApiSaveIsUndoneAndTheSettingsInForceAreSavedLater) {
  rotord::testing::FakeRotator r;
  MemoryStorage storage;
  char buf[web::Api::kMaxDocumentBytes];
  SettingsSaver saver(r.settings, kTableDefaults, storage, buf, sizeof buf);
  ASSERT_TRUE(saver.save("{}\n"));  // something is stored already
  saver.begin();
  web::Api api(web::ApiContext{*r.controller, &saver, nullptr, nullptr, "test"});
  web::HttpSession session(api);
  storage.fail = true;
  const std::string body = R"({"park.az_deg": 33})";
  rotord::testing::StringSink sink;
  session.receive(rotord::testing::post_request("/api/settings", body), sink);
  EXPECT_NE(sink.data.find("HTTP/1.1 500"), std::string::npos) << sink.data;
  EXPECT_NE(r.settings.get(Id::kParkAzDeg), 33.0);  // the API undid it
  // The revision moved (change and undo); what is stored is unknown to the
  // saver's CRC ("{}" is not this document), so it writes once the storage
  // works again, and the result is the settings in force: park.az_deg back
  // at its default, so not among the user's changes.
  storage.fail = false;
  const int saves = storage.saves;
  for (Millis t = 0; t < 20000; t += 10) saver.poll(t);
  EXPECT_EQ(storage.saves, saves + 1);
  EXPECT_NE(storage.document.find("\"settings_version\": 2"), std::string::npos);
  EXPECT_EQ(storage.document.find("park.az_deg"), std::string::npos) << storage.document;
}

}  // namespace
}  // namespace rotord
