#pragma once
// What the binding files of the Python module share: each adds its part of `tactile` to the
// module, and every call that reads files goes through with_inputs so that a missing file is a
// FileNotFoundError carrying the program's own message.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <initializer_list>
#include <memory>
#include <stdexcept>
#include <string>

namespace tactile::python {

namespace py = pybind11;

// An input file that does not exist; raised in Python as FileNotFoundError with the message
// the library gave (the one the `tactile` program prints).
class MissingFile : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Runs `work`; when it fails and one of `inputs` does not exist, the failure is that file's
// absence, whatever the reader called it.
template <typename Work>
auto with_inputs(std::initializer_list<std::filesystem::path> inputs, Work&& work) {
  try {
    return work();
  } catch (const std::exception& e) {
    for (const auto& path : inputs) {
      std::error_code ec;
      if (!path.empty() && !std::filesystem::exists(path, ec)) throw MissingFile(e.what());
    }
    throw;
  }
}

// Writes `text` to Python's sys.stdout, which a notebook shows where print() would, rather than
// to the process's own; callable from a thread that does not hold the GIL.
inline void write_python_stdout(const std::string& text) {
  py::gil_scoped_acquire locked;
  py::module_::import("sys").attr("stdout").attr("write")(text);
}

// A member of a result struct and the key it has in the dict Python gets.
template <typename S, typename T>
struct Field {
  const char* key;
  T S::*member;
};

template <typename S, typename T>
Field<S, T> field(const char* key, T S::*member) {
  return {key, member};
}

// Sets d[key] = s.member for each field, in the order given.
template <typename S, typename... T>
void put_fields(py::dict& d, const S& s, const Field<S, T>&... fields) {
  ((d[fields.key] = s.*fields.member), ...);
}

// Defines NAME(path) reading a whole file with `read` (the GIL released meanwhile) into the
// shared object the class binding of T holds.
template <typename T, typename Read>
void def_reader(py::module_& m, const char* name, Read read, const char* doc) {
  m.def(
      name,
      [read](const std::filesystem::path& path) {
        py::gil_scoped_release unlocked;
        return std::make_shared<T>(with_inputs({path}, [&] { return read(path); }));
      },
      py::arg("path"), doc);
}

// Defines NAME(path, movie) writing `movie` with `write`, the GIL released meanwhile.
template <typename T, typename Write>
void def_writer(py::module_& m, const char* name, Write write, const char* doc) {
  m.def(
      name,
      [write](const std::filesystem::path& path, const T& movie) {
        py::gil_scoped_release unlocked;
        write(path, movie);
      },
      py::arg("path"), py::arg("movie"), doc);
}

void bind_errors(py::module_& m);
void bind_movies(py::module_& m);
void bind_strain_movies(py::module_& m);
void bind_mapping(py::module_& m);
void bind_play(py::module_& m);
void bind_capture(py::module_& m);
void bind_classifier(py::module_& m);
void bind_exchange(py::module_& m);
void bind_live(py::module_& m);
void bind_synth(py::module_& m);
void bind_experiment(py::module_& m);

}  // namespace tactile::python
