#pragma once
/// Recoverable oddities found by a stage (faces dropped, a texel too small), reported to the
/// caller instead of printed: the library never writes to stderr.

#include <string>
#include <vector>

namespace geotex {

struct Diagnostic {
    std::string stage;    ///< stage that noticed it, e.g. "mesh repair"
    std::string message;  ///< one sentence, e.g. "removed 3 degenerate faces"
};

using Diagnostics = std::vector<Diagnostic>;

}  // namespace geotex
