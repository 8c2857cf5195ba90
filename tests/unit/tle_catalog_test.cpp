// The TLE store: a paste is checked whole (format, checksums, SGP4, decay)
// and stored only when every set is good; saved and loaded as text.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "memory_storage.hpp"
#include "tracking/julian.hpp"
#include "tracking/tle_catalog.hpp"

namespace rotord::tracking {
namespace {

constexpr const char* kIss =
    "ISS (ZARYA)\n"
    "1 25544U 98067A   19343.69339541  .00001764  00000-0  38792-4 0  9991\n"
    "2 25544  51.6439 211.2001 0007417  17.6667  85.6398 15.50103472202482\n";
// Vallado's set: 06251, a decaying object (SGP4 fails after some days).
constexpr const char* kSecond =
    "1 88888U          80275.98708465  .00073094  13844-3  66816-4 0    87\n"
    "2 88888  72.8435 115.9689 0086731  52.6988 110.5714 16.05824518  1058\n";

std::int64_t utc(const char* text) {
  std::int64_t ms = 0;
  EXPECT_TRUE(parse_utc(text, ms));
  return ms;
}

std::string describe(const TleCheck& c) {
  char text[160];
  c.describe(text, sizeof text);
  return text;
}

TEST(TleCatalog, StoresAPasteOfSeveralSetsAndFindsThemByNameOrNumber) {
  auto catalog = std::make_unique<TleCatalog>();
  const std::string paste = std::string(kIss) + "\r\n" + kSecond;
  const TleCheck c = catalog->put(paste, 0);
  ASSERT_TRUE(c.ok()) << describe(c);
  EXPECT_EQ(c.added, 2u);
  EXPECT_EQ(catalog->size(), 2u);
  ASSERT_NE(catalog->find("iss (zarya)"), nullptr);
  EXPECT_EQ(catalog->find("25544")->catalog, 25544u);
  EXPECT_STREQ(catalog->find("88888")->name, "88888");  // no title: its number
  EXPECT_EQ(catalog->find("nothing"), nullptr);
  Tle tle;
  ASSERT_TRUE(TleCatalog::elements(*catalog->find("25544"), tle));
  EXPECT_STREQ(tle.name, "ISS (ZARYA)");
  // The same number again replaces it.
  const TleCheck again = catalog->put(kIss, 0);
  EXPECT_EQ(again.added, 0u);
  EXPECT_EQ(again.replaced, 1u);
  EXPECT_EQ(catalog->size(), 2u);
  EXPECT_TRUE(catalog->remove(88888));
  EXPECT_FALSE(catalog->remove(88888));
  EXPECT_EQ(catalog->size(), 1u);
}

TEST(TleCatalog, RefusesABadSetAndStoresNothingOfThePaste) {
  auto catalog = std::make_unique<TleCatalog>();
  std::string bad = kIss;
  bad[bad.find("9991")] = '8';  // line 1's checksum
  const TleCheck c = catalog->put(std::string(kSecond) + bad, 0);
  EXPECT_EQ(c.problem, TleCheck::Problem::kParse);
  EXPECT_EQ(describe(c), "set 2: checksum in line 1");
  EXPECT_EQ(catalog->size(), 0u);
  EXPECT_EQ(catalog->put("hello\n", 0).problem, TleCheck::Problem::kStray);
  EXPECT_EQ(catalog->put("", 0).problem, TleCheck::Problem::kNoSets);
  // A line 1 without its line 2.
  const std::string lone = std::string(kIss).substr(0, std::string(kIss).rfind("2 25544"));
  const TleCheck l = catalog->put(lone, 0);
  EXPECT_EQ(l.problem, TleCheck::Problem::kStray) << describe(l);
  EXPECT_EQ(catalog->size(), 0u);
}

TEST(TleCatalog, RefusesAnObjectDecayedByNow) {
  auto catalog = std::make_unique<TleCatalog>();
  // The 1980 object cannot be propagated to 2019.
  const TleCheck c = catalog->put(kSecond, utc("2019-12-09T12:00:00Z"));
  EXPECT_EQ(c.problem, TleCheck::Problem::kDecayed) << describe(c);
  EXPECT_EQ(catalog->size(), 0u);
  EXPECT_TRUE(catalog->put(kIss, utc("2019-12-09T12:00:00Z")).ok());
}

TEST(TleCatalog, SavesAndLoadsThroughAStorage) {
  auto catalog = std::make_unique<TleCatalog>();
  ASSERT_TRUE(catalog->put(std::string(kIss) + kSecond, 0).ok());
  testing::MemoryStorage storage;
  auto buf = std::make_unique<char[]>(TleCatalog::kMaxTextBytes);
  ASSERT_TRUE(catalog->save(storage, buf.get(), TleCatalog::kMaxTextBytes));
  auto loaded = std::make_unique<TleCatalog>();
  loaded->load(storage, buf.get(), TleCatalog::kMaxTextBytes);
  ASSERT_EQ(loaded->size(), 2u);
  EXPECT_STREQ(loaded->entry(0).name, "ISS (ZARYA)");
  EXPECT_STREQ(loaded->entry(1).line2, catalog->entry(1).line2);
}

TEST(TleCatalog, HoldsAtMostItsCapacity) {
  auto catalog = std::make_unique<TleCatalog>();
  std::string line1 = "1 00000U 98067A   19343.69339541  .00001764  00000-0  38792-4 0  999";
  std::string line2 = "2 00000  51.6439 211.2001 0007417  17.6667  85.6398 15.50103472202482";
  std::string text;
  for (std::size_t n = 1; n <= TleCatalog::kCapacity + 1; ++n) {
    char number[6];
    std::snprintf(number, sizeof number, "%05u", static_cast<unsigned>(n));
    std::string a = line1, b = line2.substr(0, 68);
    a.replace(2, 5, number);
    b.replace(2, 5, number);
    a += static_cast<char>('0' + tle_checksum(a));
    b += static_cast<char>('0' + tle_checksum(b));
    text += a + "\n" + b + "\n";
    if (n == TleCatalog::kCapacity) {
      ASSERT_TRUE(catalog->put(text, 0).ok()) << describe(catalog->put(text, 0));
    }
  }
  EXPECT_EQ(catalog->size(), TleCatalog::kCapacity);
  auto fresh = std::make_unique<TleCatalog>();
  EXPECT_EQ(fresh->put(text, 0).problem, TleCheck::Problem::kFull);
  EXPECT_EQ(fresh->size(), 0u);
}

}  // namespace
}  // namespace rotord::tracking
