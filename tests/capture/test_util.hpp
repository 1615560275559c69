#pragma once
// Shared helpers for the capture tests: temporary folders (tests/common) and a short synthetic
// sequence.

#include "../common/temp_dir.hpp"
#include "tactile/capture/synth.hpp"

namespace tactile::capture::testing {

using tactile::test::TempDir;

// The demo's bump scene, shortened to keep the tests fast.
inline SceneSpec short_bump_scene(int frames) {
  SceneSpec spec;
  spec.scene = Scene::bump;
  spec.frame_count = frames;
  return spec;
}

}  // namespace tactile::capture::testing
