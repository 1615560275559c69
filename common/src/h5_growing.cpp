#include "tactile/common/h5_growing.hpp"

#include "tactile/common/h5.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace tactile::h5 {
namespace {

// About 64 KiB a chunk: large enough that a second of a recording is a few chunks, small
// enough that a short recording is not mostly empty chunk space.
constexpr hsize_t kChunkBytes = 64 * 1024;

}  // namespace

GrowingFile::GrowingFile(const std::filesystem::path& path) : path_(path) {
  H5::Exception::dontPrint();
  try {
    H5::FileAccPropList access;
    // SWMR needs the newest file format (HDF5 1.10 reads it).
    access.setLibverBounds(H5F_LIBVER_LATEST, H5F_LIBVER_LATEST);
    // H5F_ACC_EXCL is open(O_CREAT | O_EXCL): an existing file or a planted link fails.
    file_ = H5::H5File(path.string(), H5F_ACC_EXCL, H5::FileCreatPropList::DEFAULT, access);
  } catch (const H5::Exception& e) {
    throw std::runtime_error(fmt::format(
        "cannot create {}: {}", path.string(),
        std::filesystem::exists(path) ? std::string("it exists already") : e.getDetailMsg()));
  }
}

GrowingFile::~GrowingFile() {
  try {
    close();
  } catch (const std::exception&) {
    // A destructor cannot report; close() called before it does.
  }
}

template <typename T>
void GrowingFile::create_rows(const std::string& name, const std::vector<hsize_t>& tail,
                              const std::vector<T>& initial) {
  if (started_)
    throw std::logic_error(fmt::format("{}: dataset {} made after start", path_.string(), name));
  Rows rows;
  rows.tail = tail;
  for (hsize_t d : tail) rows.row_size *= d;
  std::vector<hsize_t> dims{0}, max_dims{H5S_UNLIMITED},
      chunk{std::max<hsize_t>(1, kChunkBytes / (sizeof(T) * rows.row_size))};
  dims.insert(dims.end(), tail.begin(), tail.end());
  max_dims.insert(max_dims.end(), tail.begin(), tail.end());
  chunk.insert(chunk.end(), tail.begin(), tail.end());
  try {
    H5::DataSpace space(static_cast<int>(dims.size()), dims.data(), max_dims.data());
    H5::DSetCreatPropList props;
    props.setChunk(static_cast<int>(chunk.size()), chunk.data());
    rows.dataset = file_.createDataSet(name, native_type<T>(), space, props);
  } catch (const H5::Exception& e) {
    throw std::runtime_error(
        fmt::format("cannot write {}: dataset {}: {}", path_.string(), name, e.getDetailMsg()));
  }
  write_rows(rows, initial);
  datasets_.emplace(name, std::move(rows));
}

void GrowingFile::start() {
  try {
    file_.flush(H5F_SCOPE_GLOBAL);
    if (H5Fstart_swmr_write(file_.getId()) < 0) {
      throw H5::FileIException("H5Fstart_swmr_write", "cannot start writing as it grows");
    }
  } catch (const H5::Exception& e) {
    throw std::runtime_error(fmt::format("cannot write {}: {}", path_.string(), e.getDetailMsg()));
  }
  started_ = true;
}

template <typename T>
void GrowingFile::write_rows(Rows& rows, const std::vector<T>& values) {
  if (values.empty()) return;
  if (values.size() % rows.row_size != 0) {
    throw std::logic_error(fmt::format("{}: {} values are not whole rows of {}", path_.string(),
                                       values.size(), rows.row_size));
  }
  const hsize_t added = values.size() / rows.row_size;
  try {
    std::vector<hsize_t> dims{rows.rows + added}, start{rows.rows}, count{added};
    dims.insert(dims.end(), rows.tail.begin(), rows.tail.end());
    start.insert(start.end(), rows.tail.size(), 0);
    count.insert(count.end(), rows.tail.begin(), rows.tail.end());
    rows.dataset.extend(dims.data());
    H5::DataSpace in_file = rows.dataset.getSpace();
    in_file.selectHyperslab(H5S_SELECT_SET, count.data(), start.data());
    H5::DataSpace in_memory(static_cast<int>(count.size()), count.data());
    rows.dataset.write(values.data(), native_type<T>(), in_memory, in_file);
  } catch (const H5::Exception& e) {
    throw std::runtime_error(fmt::format("cannot write {}: {}", path_.string(), e.getDetailMsg()));
  }
  rows.rows += added;
}

template <typename T>
void GrowingFile::append(const std::string& name, const std::vector<T>& values) {
  const auto it = datasets_.find(name);
  if (it == datasets_.end()) {
    throw std::logic_error(fmt::format("{}: no growing dataset {}", path_.string(), name));
  }
  write_rows(it->second, values);
}

void GrowingFile::set_attr(const std::string& object, const std::string& attr, std::int64_t value) {
  try {
    H5::Attribute a = file_.openGroup(object).openAttribute(attr);
    a.write(H5::PredType::NATIVE_INT64, &value);
  } catch (const H5::Exception& e) {
    throw std::runtime_error(fmt::format("cannot write {}: attribute {} of {}: {}", path_.string(),
                                         attr, object, e.getDetailMsg()));
  }
}

void GrowingFile::flush() {
  try {
    file_.flush(H5F_SCOPE_GLOBAL);
    void* handle = nullptr;
    H5::FileAccPropList access = file_.getAccessPlist();
    if (H5Fget_vfd_handle(file_.getId(), access.getId(), &handle) >= 0 && handle != nullptr) {
      if (::fsync(*static_cast<int*>(handle)) != 0) {
        throw std::runtime_error(
            fmt::format("cannot write {}: {}", path_.string(), std::strerror(errno)));
      }
    }
  } catch (const H5::Exception& e) {
    throw std::runtime_error(fmt::format("cannot write {}: {}", path_.string(), e.getDetailMsg()));
  }
}

void GrowingFile::close() {
  if (closed_) return;
  closed_ = true;
  flush();
  try {
    datasets_.clear();
    file_.close();
  } catch (const H5::Exception& e) {
    throw std::runtime_error(fmt::format("cannot write {}: {}", path_.string(), e.getDetailMsg()));
  }
}

#define TACTILE_GROWING(T)                                                                   \
  template void GrowingFile::create_rows<T>(const std::string&, const std::vector<hsize_t>&, \
                                            const std::vector<T>&);                          \
  template void GrowingFile::append<T>(const std::string&, const std::vector<T>&);
TACTILE_GROWING(double)
TACTILE_GROWING(float)
TACTILE_GROWING(std::int32_t)
#undef TACTILE_GROWING

}  // namespace tactile::h5
