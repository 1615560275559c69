// The udev rules file: named to run before logind's 73-seat-late.rules (which acts on the
// uaccess tag), tagging exactly the project's USB identity.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tactile/display/devices.hpp"

namespace tactile::display {
namespace {

// The repository's root comes from CMake: __FILE__ may be relative to the build folder (ccache
// rewrites paths under its base directory).
const std::filesystem::path kRules =
    std::filesystem::path(TACTILE_SOURCE_DIR) / "display" / "udev" / "70-tactile-display.rules";

TEST(UdevRules, SortBeforeSeatLateAndTagUaccessForOurIds) {
  // udev runs rules files in lexical order of their names.
  EXPECT_LT(kRules.filename().string(), std::string("73-seat-late.rules"));
  std::ifstream in(kRules);
  ASSERT_TRUE(in) << kRules;
  std::stringstream text;
  text << in.rdbuf();
  char vid[8];
  char pid[8];
  std::snprintf(vid, sizeof vid, "%04x", kUsbVendorId);
  std::snprintf(pid, sizeof pid, "%04x", kUsbProductId);
  int rules = 0;
  std::string line;
  while (std::getline(text, line)) {
    if (line.empty() || line[0] == '#') continue;
    ++rules;
    EXPECT_NE(line.find("TAG+=\"uaccess\""), std::string::npos) << line;
    EXPECT_NE(line.find(std::string("idVendor}==\"") + vid + "\""), std::string::npos) << line;
    EXPECT_NE(line.find(std::string("idProduct}==\"") + pid + "\""), std::string::npos) << line;
  }
  EXPECT_EQ(rules, 2);  // the USB device and its hidraw node
}

}  // namespace
}  // namespace tactile::display
