#pragma once
// BioTac-style CSV recordings (docs/formats.md, "Sensor recordings"): header
// `timestamp,tdc,tac,pdc,pac1..pac22,ele1..ele19`, one row per 10 ms; a trailing comma after
// the last field is accepted (the real recordings have one).

#include <filesystem>
#include <istream>
#include <string>

#include "tactile/perception/recording.hpp"

namespace tactile::perception {

// Throws tactile::FormatError naming the source, the line and the problem (missing or unknown
// header, wrong number of fields, non-numeric field, timestamps going back, no data rows).
SensorRecording read_sensor_csv(std::istream& in, const std::string& source);
SensorRecording read_sensor_csv(const std::filesystem::path& path);

// Writes the same layout (without the trailing comma); throws std::runtime_error on I/O errors.
void write_sensor_csv(const std::filesystem::path& path, const SensorRecording& recording);

}  // namespace tactile::perception
