#pragma once
// JSON documents on disk for the capture module's small files (model, calibration, scene):
// atomic writes and a strict first step of reading, shared with the other modules.

#include "tactile/common/atomic_file.hpp"
#include "tactile/common/json_file.hpp"

namespace tactile::capture {

using tactile::read_json_object;
using tactile::write_file_atomically;

}  // namespace tactile::capture
