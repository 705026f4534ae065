#pragma once
// geotex::Error (common/errors.hpp) as Python exceptions. The classes follow the command's
// exit codes, since that is what tells a caller whose fault a failure is:
//   geotex.Error                     base; attributes file, line, column (None, 0, 0 if unknown)
//   ├── UsageError (also ValueError)  a keyword the command would refuse as an option (exit 1)
//   ├── InputError                   the mesh, a file or arrays, is unusable (exit 2)
//   │   ├── ParseError                 malformed file content, with line and column
//   │   └── IoError (also OSError)     a file that cannot be opened or read
//   └── ProcessingError              the pipeline failed on valid input (exit 3)
//       └── NumericalError
// The message is the library's, located as the command prints it ("file:line:column: what").

#include <pybind11/pybind11.h>

#include <string>

#include "common/errors.hpp"

namespace geotex::python {

/// Which part of the work an error came from (the command's phases).
enum class Phase { Usage, Input, Processing };

/// Raises the Python exception of `phase` for a geotex::Error, its message located with
/// `file` where the error names no file of its own (empty: none). Needs the GIL.
[[noreturn]] void raise_error(Phase phase, const Error& error, const std::string& file = {});

/// Raises the Python exception of `phase` with a message of the binding's own. Needs the GIL.
[[noreturn]] void raise_error(Phase phase, const std::string& message);

/// Runs `fn` and turns a geotex::Error it throws into the exception of `phase`, as the
/// command's in_phase turns it into an exit code. `fn` may release the GIL: the error is
/// raised after it has been taken back.
template <class Fn>
auto in_phase(Phase phase, const std::string& file, Fn&& fn) -> decltype(fn()) {
    try {
        return fn();
    } catch (const Error& e) {
        raise_error(phase, e, file);
    }
}

}  // namespace geotex::python
