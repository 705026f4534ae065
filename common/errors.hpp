#pragma once
/// The one exception family of geotex. Every error that a user can cause (bad file, bad
/// option, bad data) is one of these; the CLI maps them to exit codes and one-line messages.

#include <stdexcept>
#include <string>

namespace geotex {

/// Base of all geotex errors. `file`, `line` and `column` locate the problem when known
/// (line and column are 1-based; 0 means unknown).
class Error : public std::runtime_error {
  public:
    explicit Error(const std::string& what, std::string file = {}, long line = 0, long column = 0)
        : std::runtime_error(what), file_(std::move(file)), line_(line), column_(column) {}

    const std::string& file() const noexcept { return file_; }
    long line() const noexcept { return line_; }
    long column() const noexcept { return column_; }

    /// "file:line:column: what", omitting unknown parts; `fallback_file` stands in for an
    /// unknown file (empty: no file part).
    std::string located(const std::string& fallback_file = {}) const {
        std::string out = file_.empty() ? fallback_file : file_;
        if (!out.empty() && line_ > 0) out += ':' + std::to_string(line_);
        if (!out.empty() && line_ > 0 && column_ > 0) out += ':' + std::to_string(column_);
        if (!out.empty()) out += ": ";
        return out + what();
    }

  private:
    std::string file_;
    long line_ = 0;
    long column_ = 0;
};

/// Data or arguments that violate a precondition (empty mesh, NaN coordinate, scale <= 0).
class InvalidInput : public Error {
  public:
    using Error::Error;
};

/// A file whose content does not follow its format; carries the place.
class ParseError : public Error {
  public:
    using Error::Error;
};

/// A file that cannot be opened, read or written.
class IoError : public Error {
  public:
    using Error::Error;
};

/// A computation that failed numerically (solver did not converge, overflow).
class NumericalError : public Error {
  public:
    using Error::Error;
};

}  // namespace geotex
