#pragma once
// Families of bad input shared by the reader tests: hostile numbers, cut and scrambled files,
// datasets that declare more values than any machine holds. Each test loops over a family, so
// a new field or a new reader gets every case, not only the ones someone thought of.

#include <H5Cpp.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "tactile/common/h5.hpp"

namespace tactile::testing {

// Numbers no field of any format can mean: not finite, or far outside any physical range.
inline std::vector<double> hostile_doubles() {
  const double inf = std::numeric_limits<double>::infinity();
  return {std::nan(""), inf, -inf, 1e308, -1e308, 1e-300, -1e-300};
}

// Whole numbers beyond any count, size or index a file may declare.
inline std::vector<std::int64_t> hostile_ints() {
  return {-1, std::numeric_limits<std::int32_t>::min(), std::int64_t{1} << 40,
          std::numeric_limits<std::int64_t>::max()};
}

// Replaces (or adds) a scalar attribute of `obj`.
template <typename T>
void set_attr(H5::H5Object& obj, const std::string& name, T value) {
  if (obj.attrExists(name)) obj.removeAttr(name);
  h5::write_attr(obj, name, value);
}

// Replaces dataset `name` of `group` by one of `dims` whose chunks are never written: a valid
// file of a few kilobytes declaring as many values as `dims` says.
inline void set_huge_dataset(H5::Group& group, const std::string& name,
                             const std::vector<hsize_t>& dims, const H5::PredType& type) {
  if (group.nameExists(name)) group.unlink(name);
  H5::DataSpace space(static_cast<int>(dims.size()), dims.data());
  H5::DSetCreatPropList props;
  std::vector<hsize_t> chunk(dims.size(), 1);
  props.setChunk(static_cast<int>(chunk.size()), chunk.data());
  group.createDataSet(name, type, space, props);
}

inline std::vector<char> file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void write_bytes(const std::filesystem::path& path, const std::vector<char>& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// `n` bytes from a fixed seed: the same garbage on every run.
inline std::vector<char> random_bytes(std::uint32_t seed, std::size_t n) {
  std::mt19937 rng(seed);
  std::vector<char> out(n);
  for (auto& b : out) b = static_cast<char>(rng() & 0xFF);
  return out;
}

// `bytes` with `flips` bytes past the first 8 (the signature) set to random values.
inline std::vector<char> scrambled(std::vector<char> bytes, std::uint32_t seed, int flips) {
  std::mt19937 rng(seed);
  if (bytes.size() <= 8) return bytes;
  std::uniform_int_distribution<std::size_t> at(8, bytes.size() - 1);
  for (int i = 0; i < flips; ++i) bytes[at(rng)] = static_cast<char>(rng() & 0xFF);
  return bytes;
}

}  // namespace tactile::testing
