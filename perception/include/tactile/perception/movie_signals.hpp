#pragma once
// Tactile movies as the perception evaluation's signal (paper 2's analysis applied to movies):
// a TactileMovie becomes the same SensorRecording the analysis reads from the fingertip sensor.
//
// - electrode clusters -> contactor clusters: the layout's columns (its x axis, which the
//   perception experiments place along the finger, distal = +x) split into 6 distal-proximal
//   bands, contactor column c of `cols` in cluster floor(6 (c + 0.5) / cols); a cluster's signal
//   is the mean signed deflection of its contactors (um). Each of the 19 electrode channels
//   carries the signal of its cluster (perception::kElectrodeCluster), so the analysis's cluster
//   means are the contactor cluster means;
// - pressure -> overall activity: the mean |deflection| over all contactors (um);
// - vibration -> high-frequency content: the frame-to-frame change of the overall activity (um
//   per display frame, the analogue of the AC-coupled pressure), linearly resampled to 2200 Hz.
// Rows are at 100 Hz: each row averages the display frames that start within its 10 ms. The
// movie's rest is exactly 0, so contact detection needs movie_contact_options().

#include <string>
#include <vector>

#include "tactile/movie/tactile_movie.hpp"
#include "tactile/perception/contact_inputs.hpp"
#include "tactile/perception/recording.hpp"

namespace tactile::perception {

// Cluster (0 = proximal .. 5 = distal) of every contactor, row-major.
std::vector<int> contactor_clusters(const movie::Layout& layout);

// Throws std::invalid_argument for an invalid movie (movie::validate), fewer than 6 columns or
// a movie shorter than one 100 Hz row.
perception::SensorRecording movie_signals(const movie::TactileMovie& movie,
                                          const std::string& source);

// Contact options for movie signals: the baseline (free air) is exactly 0, so contact is where
// the mean |deflection| exceeds min_threshold = 0.01 um (well below what a contactor resolves,
// well above float rounding), not 0.2 % of a baseline.
ContactOptions movie_contact_options();

}  // namespace tactile::perception
