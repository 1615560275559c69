#pragma once
// Shared helpers for the capture tests: temporary directories and a short synthetic sequence.

#include <filesystem>
#include <random>
#include <string>

#include "tactile/capture/synth.hpp"

namespace tactile::capture::testing {

// A fresh directory under the system temp dir, removed when the object goes away.
class TempDir {
 public:
  TempDir() {
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() /
            ("tactile-capture-test-" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// The demo's bump scene, shortened to keep the tests fast.
inline SceneSpec short_bump_scene(int frames) {
  SceneSpec spec;
  spec.scene = "bump";
  spec.frame_count = frames;
  return spec;
}

}  // namespace tactile::capture::testing
