#pragma once
// The provenance's fields with the names files give them (HDF5 attributes add "provenance_"),
// and the name files written before the current names gave them, if any: one list for the HDF5
// and the JSON reader and writer.

#include <array>

#include "tactile/common/provenance.hpp"

namespace tactile {

struct ProvenanceField {
  std::string Provenance::*field;
  const char* name;
  const char* former_name;  // nullptr: never named otherwise
};

inline const std::array<ProvenanceField, 6> kProvenanceFields = {{
    {&Provenance::input, "input", "source"},
    {&Provenance::program_version, "program_version", nullptr},
    {&Provenance::command_line, "command_line", nullptr},
    {&Provenance::method, "method", "mapping_method"},
    {&Provenance::parameters_json, "parameters_json", "mapping_parameters_json"},
    {&Provenance::created_utc, "created_utc", nullptr},
}};

}  // namespace tactile
