// Movies to and from the formats other tools read (MPEG-I haptics HJIF, multichannel WAV).
//
// The readers and writers live in the movie library; their bindings belong here, next to
// read_movie/write_movie in movies.cpp: export_hjif(movie, path), import_hjif(path, layout=None)
// and export_wav(movie, path), each taking and returning the Movie of movies.hpp, with the
// paths in with_inputs so that a missing file is a FileNotFoundError.

#include "bindings.hpp"

namespace tactile::python {

void bind_exchange(py::module_&) {}

}  // namespace tactile::python
