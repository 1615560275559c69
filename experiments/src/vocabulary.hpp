#pragma once
// The composing layer speaks every module's vocabulary: its sources name capture's, mapping's
// and perception's types unqualified. Only experiments' own sources include this.

#include "tactile/capture/strain_movie.hpp"
#include "tactile/mapping/map.hpp"
#include "tactile/perception/recording.hpp"

namespace tactile::experiments {

using namespace tactile::capture;
using namespace tactile::mapping;
using namespace tactile::perception;

}  // namespace tactile::experiments
