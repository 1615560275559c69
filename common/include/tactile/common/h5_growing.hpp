#pragma once
// An HDF5 file written as it grows, for a recording that a killed process must not lose.
//
// The file is created new (never over an existing file or through a link), every group,
// attribute and dataset is made first, then HDF5's single-writer/multiple-reader mode (SWMR)
// starts: from then on datasets only grow along their first dimension and integer attributes
// only change value, and HDF5 orders its metadata writes so that the file on disk is whole at
// every moment. flush() pushes everything written so far to the disk (and syncs it), so a kill
// or a power cut loses at most what came after the last flush. A file its writer never closed
// is marked as still open; open_for_reading (h5.hpp) opens such a file through SWMR reading.
//
// Datasets are chunked and not compressed: a compressed chunk changes size as it fills and
// would move, and the point of this file is that nothing written moves.

#include <H5Cpp.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace tactile::h5 {

class GrowingFile {
 public:
  // Creates `path` exclusively; throws std::runtime_error naming it and HDF5's reason.
  explicit GrowingFile(const std::filesystem::path& path);
  ~GrowingFile();
  GrowingFile(const GrowingFile&) = delete;
  GrowingFile& operator=(const GrowingFile&) = delete;

  H5::H5File& file() { return file_; }

  // A dataset at `name` (a path in the file, its group made already) of rows of `tail` numbers
  // each (empty: a vector), with `initial` rows to begin with (a row count of initial.size() /
  // prod(tail)).
  template <typename T>
  void create_rows(const std::string& name, const std::vector<hsize_t>& tail,
                   const std::vector<T>& initial = {});

  // Ends the setup: no object or attribute can be added after this.
  void start();

  // Appends whole rows (values.size() a multiple of the row's size) to a dataset made above.
  template <typename T>
  void append(const std::string& name, const std::vector<T>& values);

  // Sets an integer attribute made before start() (on the object at `object`, "/" for the root).
  void set_attr(const std::string& object, const std::string& attr, std::int64_t value);

  // Writes what HDF5 holds to the file and syncs it to the disk.
  void flush();
  // Flushes and closes (the file is then an ordinary HDF5 file again); the destructor closes
  // too, reporting nothing.
  void close();

 private:
  struct Rows {
    H5::DataSet dataset;
    std::vector<hsize_t> tail;
    hsize_t row_size = 1;
    hsize_t rows = 0;
  };
  template <typename T>
  void write_rows(Rows& rows, const std::vector<T>& values);

  std::filesystem::path path_;
  H5::H5File file_;
  std::map<std::string, Rows> datasets_;
  bool started_ = false;
  bool closed_ = false;
};

}  // namespace tactile::h5
