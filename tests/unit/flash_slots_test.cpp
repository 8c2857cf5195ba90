#include "storage/flash_slots.hpp"

#include <gtest/gtest.h>

#include <string>

#include "fake_flash.hpp"
#include "json/settings_json.hpp"
#include "settings_bases.hpp"
#include "util/crc32.hpp"
#include "web/web_api.hpp"

namespace rotord {
namespace {

using testing::FakeFlash;

// The Pico W's geometry: 4 KB erase blocks, 256-byte pages; two 8 KB slots.
constexpr std::size_t kRegion = 16 * 1024;

std::string load_all(FlashSlots& slots) {
  std::string buf(slots.capacity(), '\0');
  const long n = slots.load(buf.data(), buf.size());
  if (n < 0) return "<" + std::to_string(n) + ">";
  buf.resize(static_cast<std::size_t>(n));
  return buf;
}

std::string document(char fill, std::size_t size) {
  std::string d = "{\"v\":\"";
  d.append(size, fill);
  return d + "\"}\n";
}

TEST(Crc32, MatchesTheStandardCheckValue) {
  EXPECT_EQ(crc32("123456789", 9), 0xCBF43926u);
  EXPECT_EQ(crc32("", 0), 0u);
  // Running CRC over two pieces equals one pass.
  EXPECT_EQ(crc32("6789", 4, crc32("12345", 5)), 0xCBF43926u);
}

TEST(FlashSlots, BlankFlashHoldsNothing) {
  FakeFlash flash(kRegion, 4096, 256);
  FlashSlots slots(flash);
  ASSERT_TRUE(slots.usable());
  EXPECT_EQ(slots.capacity(), 8192u - 256u);
  EXPECT_FALSE(slots.newest());
  char buf[16];
  EXPECT_EQ(slots.load(buf, sizeof buf), -1);
}

TEST(FlashSlots, SavesAlternateBetweenSlotsWithRisingSequence) {
  FakeFlash flash(kRegion, 4096, 256);
  FlashSlots slots(flash);
  const std::string a = document('a', 700), b = document('b', 3000), c = document('c', 10);
  ASSERT_TRUE(slots.save(a));
  EXPECT_EQ(slots.newest()->slot, 0);
  EXPECT_EQ(slots.newest()->sequence, 1u);
  EXPECT_EQ(load_all(slots), a);
  ASSERT_TRUE(slots.save(b));
  EXPECT_EQ(slots.newest()->slot, 1);
  EXPECT_EQ(slots.newest()->sequence, 2u);
  EXPECT_EQ(load_all(slots), b);
  ASSERT_TRUE(slots.save(c));
  EXPECT_EQ(slots.newest()->slot, 0);
  EXPECT_EQ(slots.newest()->sequence, 3u);
  EXPECT_EQ(load_all(slots), c);
  // A reboot (a new object over the same flash) finds the same.
  FlashSlots again(flash);
  EXPECT_EQ(load_all(again), c);
}

TEST(FlashSlots, SavingTheSameDocumentWritesNothing) {
  FakeFlash flash(kRegion, 4096, 256);
  FlashSlots slots(flash);
  const std::string a = document('a', 500);
  ASSERT_TRUE(slots.save(a));
  const int erases = flash.erases, programs = flash.programs;
  ASSERT_TRUE(slots.save(a));
  EXPECT_EQ(flash.erases, erases);
  EXPECT_EQ(flash.programs, programs);
  EXPECT_EQ(slots.last_save_programmed(), 0u);
  EXPECT_EQ(slots.newest()->sequence, 1u);
  // One byte different is a change.
  std::string a2 = a;
  a2[10] = 'x';
  ASSERT_TRUE(slots.save(a2));
  EXPECT_GT(flash.programs, programs);
  EXPECT_EQ(slots.newest()->sequence, 2u);
}

TEST(FlashSlots, APowerCutWhileProgrammingKeepsThePreviousDocument) {
  const std::string old_doc = document('o', 1200);
  const std::string new_doc = document('n', 2100);
  // The save programs the payload pages, then the header page; the new
  // document counts once the 24 header bytes are in (the rest of that page
  // is 0xFF, which programs nothing).
  const long total = static_cast<long>((new_doc.size() + 255) / 256 * 256 + 256);
  const long committed = total - 256 + 24;
  for (long budget = 0; budget < committed; budget += 97) {
    SCOPED_TRACE(budget);
    FakeFlash flash(kRegion, 4096, 256);
    {
      FlashSlots slots(flash);
      ASSERT_TRUE(slots.save(document('x', 40)));
      ASSERT_TRUE(slots.save(old_doc));
      flash.program_budget = budget;
      EXPECT_FALSE(slots.save(new_doc));
    }
    flash.power_on();
    FlashSlots rebooted(flash);
    EXPECT_EQ(load_all(rebooted), old_doc);
    // And the next save after the reboot works.
    ASSERT_TRUE(rebooted.save(new_doc));
    EXPECT_EQ(load_all(rebooted), new_doc);
  }
  // One byte short of the header: still the old document; the whole
  // header: the new one.
  for (const long budget : {committed - 1, committed}) {
    FakeFlash flash(kRegion, 4096, 256);
    FlashSlots slots(flash);
    ASSERT_TRUE(slots.save(old_doc));
    flash.program_budget = budget;
    EXPECT_FALSE(slots.save(new_doc));
    flash.power_on();
    EXPECT_EQ(load_all(slots), budget < committed ? old_doc : new_doc);
  }
}

TEST(FlashSlots, APowerCutWhileErasingKeepsThePreviousDocument) {
  for (long blocks = 0; blocks < 2; ++blocks) {
    FakeFlash flash(kRegion, 4096, 256);
    FlashSlots slots(flash);
    const std::string first = document('1', 300), second = document('2', 5000);
    ASSERT_TRUE(slots.save(first));
    ASSERT_TRUE(slots.save(second));  // slot 1 newest, slot 0 holds `first`
    flash.erase_budget = blocks;      // the next save erases slot 0
    EXPECT_FALSE(slots.save(document('3', 100)));
    flash.power_on();
    EXPECT_EQ(load_all(slots), second);
  }
}

TEST(FlashSlots, ACorruptNewestSlotFallsBackToTheOlderOne) {
  FakeFlash flash(kRegion, 4096, 256);
  FlashSlots slots(flash);
  const std::string first = document('1', 300), second = document('2', 300);
  ASSERT_TRUE(slots.save(first));
  ASSERT_TRUE(slots.save(second));
  flash.mem[8192 + 256 + 100] ^= 0x04;  // one bit of slot 1's payload
  EXPECT_EQ(load_all(slots), first);
  EXPECT_EQ(slots.newest()->slot, 0);
  // Corrupt header fields are caught by the header CRC.
  flash.mem[8] ^= 0x01;  // slot 0's sequence number
  char buf[8];
  EXPECT_EQ(slots.load(buf, sizeof buf), -1);
}

TEST(FlashSlots, GarbageIsNotADocument) {
  FakeFlash flash(kRegion, 4096, 256);
  std::uint32_t x = 12345;
  for (auto& byte : flash.mem) {
    x = x * 1103515245u + 12345u;
    byte = static_cast<std::uint8_t>(x >> 16);
  }
  FlashSlots slots(flash);
  char buf[8];
  EXPECT_EQ(slots.load(buf, sizeof buf), -1);
  ASSERT_TRUE(slots.save("{}"));
  EXPECT_EQ(load_all(slots), "{}");
}

TEST(FlashSlots, LimitsAreErrorsNotCrashes) {
  FakeFlash flash(kRegion, 4096, 256);
  FlashSlots slots(flash);
  EXPECT_FALSE(slots.save(std::string(slots.capacity() + 1, 'x')));
  EXPECT_EQ(flash.erases, 0);                                   // refused before touching the flash
  ASSERT_TRUE(slots.save(std::string(slots.capacity(), 'x')));  // exactly full
  char small[16];
  EXPECT_EQ(slots.load(small, sizeof small), -2);
  ASSERT_TRUE(slots.save(""));  // an empty document is a document
  EXPECT_EQ(slots.load(small, sizeof small), 0);
}

TEST(FlashSlots, UnusableGeometryIsRefused) {
  FakeFlash one_block(4096, 4096, 256);  // no room for two slots
  FlashSlots a(one_block);
  EXPECT_FALSE(a.usable());
  EXPECT_FALSE(a.save("{}"));
  char buf[4];
  EXPECT_EQ(a.load(buf, sizeof buf), -1);
  FakeFlash big_pages(kRegion, 4096, 1024);  // pages beyond the stack buffer
  EXPECT_FALSE(FlashSlots(big_pages).usable());
  FakeFlash ok(8192, 4096, 256);  // the smallest: two 4 KB slots
  FlashSlots b(ok);
  EXPECT_TRUE(b.usable());
  EXPECT_EQ(b.capacity(), 3840u);
}

}  // namespace
}  // namespace rotord

namespace rotord {
namespace {

TEST(FlashSlots, SettingsRoundTripThroughTheWebCodec) {
  testing::FakeFlash flash(kRegion, 4096, 256);
  FlashSlots slots(flash);
  settings::Settings values;
  ASSERT_EQ(values.set(settings::Id::kAzOffsetDeg, 12.5).error, Error::kOk);
  ASSERT_EQ(values.set(settings::Id::kPinBtnCw, 13).error, Error::kOk);
  static char buf[web::Api::kMaxDocumentBytes];
  // The user's layer with every row changed fits a slot with room to grow.
  const settings::Settings base = testing::differs_everywhere(values);
  ASSERT_TRUE(web::save_settings(slots, values, base, buf, sizeof buf));
  const auto stored = static_cast<std::size_t>(slots.load(buf, sizeof buf));
  EXPECT_LT(stored * 3 / 2, slots.capacity()) << stored;

  settings::Settings loaded, scratch;
  const web::LoadOutcome outcome =
      web::load_settings(slots, base, nullptr, loaded, scratch, buf, sizeof buf);
  EXPECT_EQ(outcome.status, web::LoadOutcome::kLoaded);
  EXPECT_EQ(loaded.get(settings::Id::kAzOffsetDeg), 12.5);
  EXPECT_EQ(loaded.i(settings::Id::kPinBtnCw), 13);
  // Saving what was loaded writes nothing.
  const int erases = flash.erases;
  ASSERT_TRUE(web::save_settings(slots, loaded, base, buf, sizeof buf));
  EXPECT_EQ(flash.erases, erases);
}

}  // namespace
}  // namespace rotord

namespace rotord {
namespace {

// The wear odometer's slots on the Pico W (docs/care.md): eight 4 KB sectors
// written in turn, so each is erased once every eight saves.
TEST(FlashSlotsRing, EightSlotsAreWrittenInTurnAndAPowerCutKeepsThePrevious) {
  FakeFlash flash(32 * 1024, 4096, 256);
  FlashSlots slots(flash, 8);
  ASSERT_TRUE(slots.usable());
  EXPECT_EQ(slots.capacity(), 4096u - 256u);
  for (int n = 0; n < 16; ++n) {
    ASSERT_TRUE(slots.save(document(static_cast<char>('a' + n), 900)));
    ASSERT_TRUE(slots.newest().has_value());
    EXPECT_EQ(slots.newest()->slot, n % 8);
    EXPECT_EQ(load_all(slots), document(static_cast<char>('a' + n), 900));
  }
  EXPECT_EQ(flash.erases, 16);  // each sector twice in sixteen saves
  // The power fails while the next slot is being programmed: the last
  // complete record stays the newest.
  flash.program_budget = 512;
  EXPECT_FALSE(slots.save(document('z', 900)));
  flash.power_on();
  EXPECT_EQ(slots.newest()->slot, 7);
  EXPECT_EQ(load_all(slots), document('p', 900));
}

}  // namespace
}  // namespace rotord
