#pragma once
// The message of what a piece of code throws, for assertions on the wording of errors.

#include <exception>
#include <string>

namespace tactile::test {

// The message of the exception of type E (any std::exception by default) that `f` throws, or
// "(no error)" when it throws nothing, so that an assertion on the message fails readably; an
// exception of another type passes through and fails the test.
template <typename E = std::exception, typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace tactile::test
