#include "tactile/capture/pore_training_io.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>

#include "tactile/capture/image.hpp"
#include "tactile/common/csv.hpp"
#include "tactile/common/error.hpp"

namespace tactile::capture {

namespace fs = std::filesystem;

namespace {

constexpr const char* kImageExtensions = "jpg|jpeg|png|bmp|tif|tiff";

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// "NN" of `prefix`NN, when `stem` has that shape with NN all digits.
std::optional<std::string> number_after(const std::string& stem, const std::string& prefix) {
  if (stem.size() <= prefix.size() || stem.rfind(prefix, 0) != 0) return std::nullopt;
  const std::string nn = stem.substr(prefix.size());
  if (!std::all_of(nn.begin(), nn.end(), [](unsigned char c) { return std::isdigit(c); })) {
    return std::nullopt;
  }
  return nn;
}

// `ext` (".jpg", lower case) is one of kImageExtensions.
bool is_image_extension(const std::string& ext) {
  if (ext.size() < 2 || ext[0] != '.') return false;
  const std::string_view list = kImageExtensions, name = std::string_view(ext).substr(1);
  for (std::size_t at = 0; at <= list.size();) {
    const std::size_t bar = std::min(list.find('|', at), list.size());
    if (list.substr(at, bar - at) == name) return true;
    at = bar + 1;
  }
  return false;
}

struct Pair {
  fs::path image;
  fs::path marks;
};

// Orders NN numerically (2 before 10) without converting it, which could overflow.
using PrintKey = std::pair<std::size_t, std::string>;  // digits after leading zeros, NN

PrintKey print_key(const std::string& nn) {
  const std::size_t first = std::min(nn.find_first_not_of('0'), nn.size());
  return {nn.size() - first, nn};
}

// Image and marks files of `dir` by NN, in numeric order of NN.
std::map<PrintKey, Pair> find_pairs(const fs::path& dir) {
  std::map<PrintKey, Pair> pairs;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (!entry.is_regular_file()) continue;
    const fs::path& path = entry.path();
    const std::string ext = lower(path.extension().string());
    const std::string stem = path.stem().string();
    std::optional<std::string> nn;
    fs::path Pair::*slot = nullptr;
    if (is_image_extension(ext)) {
      nn = number_after(stem, "image_");
      slot = &Pair::image;
    } else if (ext == ".txt") {
      nn = number_after(stem, "pores_");
      slot = &Pair::marks;
    }
    if (!nn) continue;
    Pair& pair = pairs[print_key(*nn)];
    if (!(pair.*slot).empty()) {
      throw FormatError(fmt::format("{}: two files for print {}: {} and {}", dir.string(), *nn,
                                    (pair.*slot).filename().string(), path.filename().string()));
    }
    pair.*slot = path;
  }
  return pairs;
}

std::optional<double> parse_number(const std::string& token) {
  double value = 0;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

}  // namespace

std::vector<std::array<double, 2>> read_pore_marks(const fs::path& path, int width_px,
                                                   int height_px) {
  std::ifstream in(path);
  if (!in) throw FormatError(fmt::format("{}: cannot open marks file", path.string()));
  std::vector<std::array<double, 2>> marks;
  std::string line;
  csv::LineReader lines(in);
  while (lines.next(line)) {
    const std::size_t line_no = lines.number();
    const std::string where = fmt::format("{}:{}", path.string(), line_no);
    std::istringstream words(line);
    std::vector<std::string> tokens;
    for (std::string t; words >> t;) tokens.push_back(t);
    if (tokens.empty()) continue;  // blank lines (a trailing one is common) carry no mark
    if (tokens.size() == 1) {
      throw FormatError(
          fmt::format("{}: expected two numbers 'row col', found only '{}'", where, tokens[0]));
    }
    if (tokens.size() > 2) {
      throw FormatError(
          fmt::format("{}: extra columns after 'row col' (expected two numbers, found {} fields)",
                      where, tokens.size()));
    }
    const auto row = parse_number(tokens[0]);
    const auto col = parse_number(tokens[1]);
    if (!row || !col) {
      throw FormatError(fmt::format("{}: expected two numbers 'row col', found '{}'", where,
                                    tokens[row ? 1 : 0]));
    }
    if (*row < 1 || *row > height_px || *col < 1 || *col > width_px) {
      throw FormatError(fmt::format(
          "{}: mark at row {} col {} lies outside the {} x {} px image (1-based: rows 1..{}, "
          "cols 1..{})",
          where, *row, *col, width_px, height_px, height_px, width_px));
    }
    marks.push_back({*col - 1, *row - 1});
  }
  if (marks.empty()) {
    throw FormatError(fmt::format(
        "{}: no marks (expected one pore per line as 'row col', 1-based pixels)", path.string()));
  }
  return marks;
}

std::vector<fs::path> pore_training_files(const fs::path& dir) {
  std::vector<fs::path> files;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return files;
  for (const auto& [key, pair] : find_pairs(dir)) {
    for (const fs::path* file : {&pair.image, &pair.marks}) {
      if (!file->empty()) files.push_back(*file);
    }
  }
  return files;
}

std::vector<PoreTrainingPrint> read_pore_training_prints(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw FormatError(fmt::format("{}: no such directory of marked prints", dir.string()));
  }
  const auto pairs = find_pairs(dir);
  if (pairs.empty()) {
    throw FormatError(
        fmt::format("{}: no marked prints (expected image_NN.{} with pores_NN.txt beside each)",
                    dir.string(), kImageExtensions));
  }
  // Every pair is checked before any image is decoded, so a missing file fails at once.
  for (const auto& [key, pair] : pairs) {
    if (pair.marks.empty()) {
      throw FormatError(fmt::format("{}: image without its marks file pores_{}.txt",
                                    pair.image.string(), key.second));
    }
    if (pair.image.empty()) {
      throw FormatError(fmt::format("{}: marks without their image image_{}.{}",
                                    pair.marks.string(), key.second, kImageExtensions));
    }
  }
  std::vector<PoreTrainingPrint> prints;
  for (const auto& [key, pair] : pairs) {
    PoreTrainingPrint print;
    print.name = pair.image.filename().string();
    print.image = read_image(pair.image);
    print.pores_px = read_pore_marks(pair.marks, print.image.width_px, print.image.height_px);
    prints.push_back(std::move(print));
  }
  return prints;
}

}  // namespace tactile::capture
