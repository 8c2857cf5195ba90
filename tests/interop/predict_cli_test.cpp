// rotord predict / rotord passes, the real binary with no daemon: its CSV
// against the tracking layer's reference data (tests/data/tracking, made by
// skyfield, python-sgp4 and PyEphem), and every kind of bad input refused with
// a message and exit status 2.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "shell.hpp"

namespace rotord::testing {
namespace {

const std::string kRotord = ROTORD_BINARY;
const std::string kData = ROTORD_TRACKING_DATA_DIR;

std::vector<std::vector<std::string>> csv(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> fields;
    std::istringstream l(line);
    std::string f;
    while (std::getline(l, f, ',')) fields.push_back(f);
    rows.push_back(fields);
  }
  return rows;
}

std::vector<std::vector<std::string>> read_csv(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return csv(s.str());
}

double angle_diff(double a, double b) {
  double d = std::fmod(a - b + 540.0, 360.0) - 180.0;
  return std::fabs(d);
}

class PredictCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = make_temp_dir("rotord-predict");
    tle_ = dir_ + "/stations.txt";
    std::ofstream(tle_)
        << "HUBBLE\r\n"
           "1 20580U 90037B   19342.88042116  .00000361  00000-0  11007-4 0  9996\r\n"
           "2 20580  28.4682 146.6676 0002639 185.9222 332.7009 15.09228242 21532\r\n"
           "ISS (ZARYA)\r\n"
           "1 25544U 98067A   19343.69339541  .00001764  00000-0  38792-4 0  9991\r\n"
           "2 25544  51.6439 211.2001 0007417  17.6667  85.6398 15.50103472202482\r\n";
  }
  void TearDown() override { run_command("rm -rf " + dir_); }

  /// Runs rotord with `args`; stdout only (stderr to a file, read back on failure).
  CommandOutput rotord(const std::string& args) {
    CommandOutput r = run_command("(" + kRotord + " " + args + " 2>" + dir_ + "/stderr)");
    std::ifstream err(dir_ + "/stderr");
    std::stringstream s;
    s << err.rdbuf();
    stderr_ = s.str();
    return r;
  }

  std::string dir_, tle_, stderr_;
};

TEST_F(PredictCli, PredictPrintsTheIssPassAsTheReferenceSeesIt) {
  const CommandOutput r =
      rotord("predict --tle " + tle_ +
             " --name 'ISS (ZARYA)' --lat 40.015 --lon -105.27 --alt 1655"
             " --from 2019-12-09T17:50:00Z --to 2019-12-09T18:05:00Z --step 60");
  ASSERT_EQ(r.rc, 0) << stderr_;
  const auto rows = csv(r.out);
  ASSERT_EQ(rows.size(), 17u) << r.out;  // header + 16 minutes, both ends
  EXPECT_EQ(rows[0], (std::vector<std::string>{"utc", "az_deg", "el_deg", "range_km"}));
  EXPECT_EQ(rows[1][0], "2019-12-09T17:50:00Z");
  EXPECT_EQ(rows[16][0], "2019-12-09T18:05:00Z");
  int compared = 0;
  for (const auto& ref : read_csv(kData + "/satellites.csv")) {
    if (ref.size() != 12 || ref[0] != "ISS" || ref[2] != "40.0150") continue;
    for (std::size_t i = 1; i < rows.size(); ++i) {
      if (rows[i][0] != ref[1]) continue;
      // The same simplified chain (0.001 deg: printed to 3 decimals)...
      EXPECT_LT(angle_diff(std::stod(rows[i][1]), std::stod(ref[5])), 0.001) << ref[1];
      EXPECT_NEAR(std::stod(rows[i][2]), std::stod(ref[6]), 0.001) << ref[1];
      EXPECT_NEAR(std::stod(rows[i][3]), std::stod(ref[7]), 0.002) << ref[1];
      // ... and skyfield's full model, within the tolerances.
      if (std::stod(ref[10]) < 80.0) {
        EXPECT_LT(angle_diff(std::stod(rows[i][1]), std::stod(ref[9])), 0.06) << ref[1];
      }
      EXPECT_NEAR(std::stod(rows[i][2]), std::stod(ref[10]), 0.03) << ref[1];
      ++compared;
    }
  }
  EXPECT_GE(compared, 12);  // the reference keeps the minutes above -5 deg
}

TEST_F(PredictCli, PredictIncludesAnEndThatIsNotOnAStep) {
  const CommandOutput r = rotord(
      "predict --body moon --lat 51 --lon 0 --alt 0 --from 2024-03-20T00:00:00Z"
      " --to 2024-03-20T00:00:10Z --step 4");
  ASSERT_EQ(r.rc, 0) << stderr_;
  const auto rows = csv(r.out);
  ASSERT_EQ(rows.size(), 5u) << r.out;
  EXPECT_EQ(rows[3][0], "2024-03-20T00:00:08Z");
  EXPECT_EQ(rows[4][0], "2024-03-20T00:00:10Z");
}

TEST_F(PredictCli, PassesMatchTheReferencePasses) {
  const CommandOutput r =
      rotord("passes --tle " + tle_ +
             " --name 'iss (zarya)' --lat 51.5074 --lon -0.1278 --alt 20"
             " --from 2019-12-09T12:00:00Z --to 2019-12-10T12:00:00Z --min-el 10");
  ASSERT_EQ(r.rc, 0) << stderr_;
  const auto rows = csv(r.out);
  ASSERT_GE(rows.size(), 2u) << r.out;
  EXPECT_EQ(rows[0], (std::vector<std::string>{"aos_utc", "los_utc", "max_el_deg", "max_el_utc",
                                               "aos_az_deg", "los_az_deg"}));
  int reference = 0;
  for (const auto& ref : read_csv(kData + "/passes.csv")) {
    if (ref.size() != 11 || ref[0] != "ISS" || ref[1] != "51.5074" || ref[4] != "10.0") continue;
    ++reference;
    // The reference has milliseconds; rotord prints whole seconds.
    const std::string aos = ref[7].substr(0, 19), los = ref[8].substr(0, 19);
    bool found = false;
    for (std::size_t i = 1; i < rows.size(); ++i) {
      if (rows[i][0].substr(0, 16) != aos.substr(0, 16)) continue;
      found = true;
      EXPECT_NEAR(std::stod(rows[i][2]), std::stod(ref[10]), 0.01);
      EXPECT_EQ(rows[i][1].substr(0, 16), los.substr(0, 16));
    }
    EXPECT_TRUE(found) << "no pass with AOS " << ref[7] << " in\n" << r.out;
  }
  EXPECT_GE(reference, 2);
  EXPECT_EQ(static_cast<int>(rows.size()) - 1, reference) << r.out;
}

TEST_F(PredictCli, TheSunRisesAndSetsOnTheEquinox) {
  const CommandOutput r = rotord(
      "passes --body sun --lat 51.4769 --lon 0 --alt 0"
      " --from 2024-03-20T00:00:00Z --to 2024-03-21T00:00:00Z");
  ASSERT_EQ(r.rc, 0) << stderr_;
  const auto rows = csv(r.out);
  ASSERT_EQ(rows.size(), 2u) << r.out;
  EXPECT_EQ(rows[1][0].substr(0, 15), "2024-03-20T06:0");  // rises about 06:07 UTC
  EXPECT_EQ(rows[1][1].substr(0, 15), "2024-03-20T18:0");  // sets about 18:08 UTC
  EXPECT_NEAR(std::stod(rows[1][4]), 90.0, 1.0);           // due east
  EXPECT_NEAR(std::stod(rows[1][5]), 270.0, 1.0);          // due west
}

TEST_F(PredictCli, BadInputGetsAMessageAndExitStatus2) {
  const std::string where = " --lat 40 --lon -105 --alt 1600";
  const std::string when = " --from 2019-12-09T12:00:00Z --to 2019-12-09T13:00:00Z";
  std::ofstream(dir_ + "/bad.tle")
      << "1 25544U 98067A   19343.69339541  .00001764  00000-0  38792-4 0  9992\n"
         "2 25544  51.6439 211.2001 0007417  17.6667  85.6398 15.50103472202482\n";
  std::ofstream(dir_ + "/empty.tle") << "nothing here\n";
  struct Case {
    std::string args;
    std::string message;  // part of the line on stderr
  };
  const Case cases[] = {
      {"predict --tle " + dir_ + "/missing.tle" + where + when + " --step 60", "cannot read"},
      {"predict --tle " + dir_ + where + when + " --step 60", "cannot read"},  // a directory
      {"predict --tle /dev/zero" + where + when + " --step 60", "over 64 MiB"},
      {"predict --tle " + dir_ + "/bad.tle" + where + when + " --step 60", "checksum"},
      {"predict --tle " + dir_ + "/empty.tle" + where + when + " --step 60", "no two-line"},
      {"predict --tle " + tle_ + " --name NOSUCH" + where + when + " --step 60", "NOSUCH"},
      {"predict --body mars" + where + when + " --step 60", "mars"},
      {"predict --body sun --tle " + tle_ + where + when + " --step 60", "excludes"},
      {"predict" + where + when + " --step 60", "--tle FILE or --body"},
      {"predict --body sun --lat 95 --lon 0 --alt 0" + when + " --step 60", "--lat"},
      {"predict --body sun --lat 0 --lon 200 --alt 0" + when + " --step 60", "--lon"},
      {"predict --body sun" + where + " --from 2019-12-09 --to 2019-12-09T13:00:00Z --step 60",
       "--from"},
      {"predict --body sun" + where +
           " --from 2019-12-09T12:00:00Z --to 2019-13-09T13:00:00Z"
           " --step 60",
       "--to"},
      {"predict --body sun" + where +
           " --from 2019-12-09T14:00:00Z --to 2019-12-09T13:00:00Z --step 60",
       "before"},
      {"predict --body sun" + where + when + " --step 0", "--step"},
      {"predict --body sun" + where + when, "--step"},
      {"predict --body sun" + where +
           " --from 2019-01-01T00:00:00Z --to 2029-01-01T00:00:00Z"
           " --step 1",
       "10 million"},
      {"passes --body sun" + where + when + " --min-el 91", "--min-el"},
      {"passes --tle " + dir_ + "/bad.tle" + where + when, "checksum"},
  };
  for (const Case& c : cases) {
    const CommandOutput r = rotord(c.args);
    EXPECT_EQ(r.rc, 2) << c.args << "\n" << stderr_;
    EXPECT_NE(stderr_.find(c.message), std::string::npos) << c.args << "\n" << stderr_;
    EXPECT_EQ(r.out, "") << c.args;  // nothing on stdout: no partial table
  }
}

TEST_F(PredictCli, ADecayedObjectIsRefusedNotPrinted) {
  // MINOTAUR R/B (Vallado's verification set) decays within an hour of its epoch.
  std::ofstream(dir_ + "/decayed.tle")
      << "1 28872U 05037B   05333.02012661  .25992681  00000-0  24476-3 0  1534\n"
         "2 28872  96.4736 157.9986 0303955 244.0492 110.6523 16.46015938 10708\n";
  const CommandOutput r = rotord("predict --tle " + dir_ +
                                 "/decayed.tle --lat 0 --lon 0 --alt 0 --from "
                                 "2005-11-29T00:30:00Z --to 2005-11-29T03:00:00Z --step 60");
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(stderr_.find("decayed"), std::string::npos) << stderr_;
  EXPECT_EQ(r.out, "");
}

}  // namespace
}  // namespace rotord::testing
