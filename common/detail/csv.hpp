#pragma once
// RFC 4180 CSV: the reader of batch manifests and the field writer of every CSV geotex
// writes (query results, batch and publish summaries). Written by hand: no Debian package
// offers a small CSV reader that reports line numbers.

#include <string>
#include <string_view>
#include <vector>

namespace geotex::detail {

struct CsvRow {
    std::vector<std::string> fields;
    long line = 0;  ///< 1-based line where the row starts
};

/// Rows of `text` (LF or CRLF line ends, a leading UTF-8 byte-order mark ignored, empty
/// lines skipped; quoted fields may hold commas, doubled quotes and line breaks). Throws
/// ParseError naming `file` and the line for a quote that is never closed or text after a
/// closing quote.
std::vector<CsvRow> parse_csv(std::string_view text, const std::string& file);

/// `field` as one CSV field: quoted when it holds a comma, a quote or a line break.
std::string csv_field(std::string_view field);

}  // namespace geotex::detail
