// The live session's parts that need no camera: the queue that drops the oldest frame instead
// of waiting, the request built from the capture and map requests' rows, and a session on a
// thread of its own.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <fstream>
#include <thread>

#include "../common/temp_dir.hpp"
#include "tactile/common/error.hpp"
#include "tactile/live/frame_queue.hpp"
#include "tactile/live/live_request.hpp"
#include "tactile/live/live_session.hpp"

namespace {

using tactile::OptionSpelling;
using tactile::live::DropOldestQueue;
using ::testing::HasSubstr;

TEST(DropOldestQueue, AFullQueueDropsItsOldestAndCountsIt) {
  DropOldestQueue<int> q(2);
  EXPECT_FALSE(q.push(1).has_value());
  EXPECT_FALSE(q.push(2).has_value());
  EXPECT_EQ(q.push(3), 1);  // the oldest goes, the push does not wait
  EXPECT_EQ(q.push(4), 2);
  EXPECT_EQ(q.dropped(), 2);
  EXPECT_EQ(q.pop(std::chrono::milliseconds(0)), 3);
  EXPECT_EQ(q.pop(std::chrono::milliseconds(0)), 4);
  EXPECT_FALSE(q.pop(std::chrono::milliseconds(0)).has_value());
}

TEST(DropOldestQueue, PopWaitsForAPushAndEndsOnClose) {
  DropOldestQueue<int> q(1);
  std::thread producer([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    q.push(7);
    q.close();
  });
  EXPECT_EQ(q.pop(std::chrono::seconds(5)), 7);
  EXPECT_FALSE(q.pop(std::chrono::seconds(5)).has_value());
  EXPECT_TRUE(q.closed_and_empty());
  producer.join();
}

tactile::live::LiveRequest request_for(const std::filesystem::path& source) {
  tactile::live::LiveRequest r;
  r.source = source.string();
  r.capture.px_per_mm = 47;
  return r;
}

std::string error_of(const tactile::live::LiveRequest& r) {
  try {
    tactile::live::resolve(r, OptionSpelling::cli);
  } catch (const tactile::RequestError& e) {
    return e.what();
  }
  return {};
}

TEST(LiveRequest, TakesCaptureAndMapRowsAsTheyAre) {
  const auto& live = tactile::live::live_options();
  for (const char* name : {"px_per_mm", "rate_hz", "pores"}) {
    const auto* mine = tactile::find_option(live, name);
    const auto* theirs = tactile::find_option(tactile::capture::capture_options(), name);
    ASSERT_NE(mine, nullptr) << name;
    EXPECT_EQ(mine->help, theirs->help) << name;
    EXPECT_EQ(mine->min, theirs->min) << name;
    EXPECT_EQ(mine->max, theirs->max) << name;
  }
  const auto* gain = tactile::find_option(live, "gain");
  ASSERT_NE(gain, nullptr);
  EXPECT_EQ(gain->shown(tactile::live::LiveRequest{}),
            tactile::find_option(tactile::mapping::map_options(), "gain")
                ->shown(tactile::mapping::MapRequest{}));
}

TEST(LiveRequest, RefusesWhatASessionCannotDo) {
  const tactile::test::TempDir dir("live");
  auto r = request_for(dir.path());
  EXPECT_EQ(error_of(r), "");
  r.map.params.method = tactile::mapping::MappingMethod::profile;
  EXPECT_THAT(error_of(r), HasSubstr("--method: profile needs a surface profile"));
  r = request_for(dir.path());
  r.map.params.normalisation = tactile::mapping::Normalisation::peak;
  EXPECT_THAT(error_of(r), HasSubstr("normalisation needs the whole movie"));
  r = request_for(dir.path());
  r.capture.px_per_mm.reset();
  EXPECT_THAT(error_of(r), HasSubstr("give one of --calib"));
  r = request_for(dir.path() / "absent");
  EXPECT_THAT(error_of(r), HasSubstr("no such file or folder"));
}

TEST(LiveRequest, RecordsOnlyIntoANewOrEmptyFolder) {
  const tactile::test::TempDir dir("live");
  auto r = request_for(dir.path());
  r.record = dir.path() / "session";
  EXPECT_EQ(error_of(r), "");
  std::filesystem::create_directories(*r.record);
  EXPECT_EQ(error_of(r), "");
  std::ofstream(*r.record / "latency.csv") << "earlier\n";
  EXPECT_THAT(error_of(r), HasSubstr("is not an empty folder"));
}

TEST(LiveRequest, DevicesAndStreamsAreNotFiles) {
  EXPECT_FALSE(tactile::live::is_rehearsal_source("/dev/video0"));
  EXPECT_FALSE(tactile::live::is_rehearsal_source("udp://127.0.0.1:5000"));
  EXPECT_TRUE(tactile::live::is_rehearsal_source("frames/"));
  EXPECT_TRUE(tactile::live::is_rehearsal_source("session.mkv"));
}

TEST(SessionThread, WhatTheSessionThrowsComesBackFromResultAfterOnEnd) {
  const tactile::test::TempDir dir("live");  // a folder with no frames: the source fails
  const auto session = tactile::live::resolve(request_for(dir.path()), OptionSpelling::cli);
  tactile::display::EmulatedDevice device(tactile::live::emulated_display_options(session.layout));
  std::atomic<bool> stop{false};
  std::atomic<int> ended{0};
  tactile::live::SessionThread worker(session, device, stop, {}, [&] { ++ended; });
  try {
    worker.result();
    ADD_FAILURE() << "a session without frames returned a summary";
  } catch (const tactile::FormatError& e) {
    EXPECT_THAT(e.what(), HasSubstr("no image files"));
  }
  EXPECT_TRUE(worker.done());
  EXPECT_EQ(ended.load(), 1);
  EXPECT_FALSE(stop.load());  // it ended by itself
}

}  // namespace
