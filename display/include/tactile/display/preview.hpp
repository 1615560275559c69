#pragma once
// A PNG that shows a tactile movie without a screen: a strip of evenly spaced frames (each the
// contactor grid displaced by its magnified deflection, coloured by stretch/compression, with
// its time) above a plot of activity (RMS deflection per frame) against time.

#include <filesystem>

#include "tactile/movie/tactile_movie.hpp"

namespace tactile::display {

struct PreviewOptions {
  int frames = 8;            // panels in the strip, evenly spaced from first to last frame
  int panel_px = 200;        // each panel is panel_px x panel_px
  int plot_height_px = 200;  // activity plot below the strip
  double magnification = 0;  // deflection drawing scale; 0 = movie::auto_magnification(movie)
};

// Image size: width = frames * panel_px; height = kPreviewHeaderPx + panel_px +
// kPreviewLabelPx + plot_height_px (header: title, colour scale and deflection scale bar;
// label: each panel's time).
inline constexpr int kPreviewHeaderPx = 60;
inline constexpr int kPreviewLabelPx = 24;

// Throws std::invalid_argument for an invalid movie or options (fewer than 1 frame or panels
// under 40 px), std::runtime_error if the PNG cannot be written. A movie of fewer frames than
// options.frames gets one panel per frame, but the image keeps its documented size.
void write_preview_strip(const std::filesystem::path& png, const movie::TactileMovie& movie,
                         const PreviewOptions& options = {});

}  // namespace tactile::display
