#pragma once
// Hand-marked prints in the PolyU HRF layout, for training the pore model: a directory of
// image_NN.<jpg|jpeg|png|bmp|tif|tiff> with pores_NN.txt beside each, one marked pore per line
// as `row col` (1-based pixel coordinates, separated by white space).

#include <array>
#include <filesystem>
#include <vector>

#include "tactile/capture/pore_training.hpp"

namespace tactile::capture {

// Every image/marks pair of `dir`, in order of NN, pores converted to 0-based x, y. Throws
// tactile::FormatError naming the file (and line) for: a missing directory or one without
// pairs, an image without its marks file or marks without their image, a line that is not two
// numbers or has extra columns, a mark outside its image, a marks file without marks, an
// unreadable image.
std::vector<PoreTrainingPrint> read_pore_training_prints(const std::filesystem::path& dir);

// The image and marks files read_pore_training_prints would read from `dir` (none if it is not a
// directory), without reading them: for a caller that must not write over them.
std::vector<std::filesystem::path> pore_training_files(const std::filesystem::path& dir);

// One marks file as 0-based (x, y); `width_px` x `height_px` is its image's size. Throws
// tactile::FormatError naming the file and line (not two numbers, extra columns, a mark outside
// the image, no marks at all).
std::vector<std::array<double, 2>> read_pore_marks(const std::filesystem::path& path, int width_px,
                                                   int height_px);

}  // namespace tactile::capture
