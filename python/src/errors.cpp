// The project's exceptions as Python exceptions, with the messages the `tactile` program prints.

#include <string_view>

#include "bindings.hpp"
#include "tactile/common/error.hpp"
#include "tactile/display/transport.hpp"

namespace tactile::python {

void bind_errors(py::module_& m) {
  // A file that does not follow its format is an error about a file, as h5py and json's
  // readers of damaged files report it: an OSError.
  static py::exception<FormatError> format_error(m, "FormatError", PyExc_OSError);
  format_error.doc() = "A file that does not follow its documented format (names file and field).";
  static py::exception<display::TransportError> device_error(m, "DeviceError", PyExc_OSError);
  device_error.doc() = "A display that failed, was unplugged or refused a request.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const py::builtin_exception& e) {
      e.set_error();  // pybind11's own (type_error, value_error): runtime_errors too
    } catch (const MissingFile& e) {
      PyErr_SetString(PyExc_FileNotFoundError, e.what());
    } catch (const FormatError& e) {
      format_error(e.what());
    } catch (const display::TransportError& e) {
      device_error(e.what());
    } catch (const std::invalid_argument& e) {
      // Bad arguments, and outputs over inputs (OutputPathError): a usage error, exit 2 in the CLI.
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const std::runtime_error& e) {
      // Every failed write says "cannot write PATH: <the system's reason>" (atomic_write.hpp).
      const bool write_failed = std::string_view(e.what()).starts_with("cannot write ");
      PyErr_SetString(write_failed ? PyExc_OSError : PyExc_RuntimeError, e.what());
    }
  });
}

}  // namespace tactile::python
