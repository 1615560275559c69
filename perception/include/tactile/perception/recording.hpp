#pragma once
// A recording of a BioTac-style multimodal fingertip sensor (paper 2): overall fluid pressure
// and 19 electrode impedances sampled at 100 Hz, vibration (the AC pressure channel) at 2200 Hz,
// i.e. 22 vibration samples per 100 Hz row. Values are raw sensor counts, as in the CSV files.

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace tactile::perception {

inline constexpr int kElectrodeCount = 19;
inline constexpr int kVibrationPerRow = 22;
inline constexpr int kElectrodeClusterCount = 6;

// Electrode -> distal-proximal cluster (0 = most proximal ... 5 = tip), for the layout of
// sensor_electrode_positions() (docs/perception-models.md).
inline constexpr std::array<int, kElectrodeCount> kElectrodeCluster = {
    0, 1, 2, 3, 4, 5,  // E1-E6: radial column, proximal to distal
    5, 5, 5, 4,        // E7-E10: around the tip
    0, 1, 2, 3, 4, 5,  // E11-E16: ulnar column
    1, 2, 3};          // E17-E19: centre column

struct SensorRecording {
  std::string source;      // file name or "simulated ..." (for messages)
  double rate_hz = 100.0;  // pressure and electrode rows
  double vibration_rate_hz = 2200.0;
  std::vector<double> t_s;  // one per row
  std::vector<double> temperature_dc;
  std::vector<double> temperature_ac;
  std::vector<double> pressure;                                 // pdc: overall fluid pressure
  std::array<std::vector<double>, kElectrodeCount> electrodes;  // ele1..ele19
  std::vector<double> vibration;  // pac, kVibrationPerRow per row, in time order

  std::size_t rows() const { return t_s.size(); }
};

}  // namespace tactile::perception
