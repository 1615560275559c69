#pragma once
// The current UTC time as ISO 8601, defined beside the provenance (which stamps it) so that a
// program using provenances without HDF5 (tests/vm's guest client) needs no HDF5 for it;
// h5::utc_now_iso8601 is this.

#include <string>

namespace tactile {

// SOURCE_DATE_EPOCH, when set, is taken as the time (reproducible output); a value that is not
// whole seconds from 0 to 253402300799 is std::invalid_argument naming it.
std::string utc_now_iso8601();

}  // namespace tactile
