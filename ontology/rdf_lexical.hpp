#pragma once
// Lexical forms and checks of the RDF writer: every string that goes into a triple passes one
// of these, so that hostile names, labels and IRIs are refused with a clear message or
// escaped, never written broken. Internal to ontology/.

#include <string>
#include <string_view>

namespace geotex::rdf_detail {

/// Two upper-case hexadecimal digits of a byte.
std::string hex2(unsigned v);

bool is_ascii_alpha(char c);
bool is_ascii_digit(char c);

/// Throws InvalidInput unless `s` is valid UTF-8 that all three syntaxes can carry (no NUL,
/// no C0 control but tab, line feed and carriage return, no DEL, no U+FFFE/U+FFFF).
void check_text(std::string_view s, const std::string& what);

/// xsd:dateTime lexical form: -?YYYY-MM-DDThh:mm:ss(.s+)?(Z|(+|-)hh:mm)?
bool is_date_time(const std::string& t);

/// Throws InvalidInput unless `tag` is a language tag (detail::is_language_tag).
void check_language(const std::string& tag, const std::string& what);

bool is_lower_hex(const std::string& s);

/// Throws InvalidInput unless `hex` is 64 lower-case hexadecimal digits.
void check_sha256(const std::string& hex, const std::string& what);

/// One path segment of an IRI: everything but RFC 3986 unreserved characters is
/// percent-encoded (UTF-8 bytes included), so an id can never add a segment, a query or a
/// fragment; "." and ".." are encoded too, as IRI resolution would remove them.
std::string iri_segment(std::string_view id);

/// Shortest lexical form that reads back to the same double, always with a mantissa dot and
/// an exponent ("1.25E1", "1.0E-1", "-0.0E0"), so that Turtle writes it as a double. Throws
/// InvalidInput for a value that is not finite.
std::string double_lexical(double v, const std::string& what);

/// The text of a string body with the escapes that SPARQL, Turtle and N-Triples share
/// resolved: \t \b \n \r \f \" \' \\ and \uXXXX, \UXXXXXXXX (as UTF-8). A \u or \U without
/// its hexadecimal digits stays as written; any other escaped character stands for itself.
std::string unescape_string_body(std::string_view body);

/// Canonical xsd:decimal ("-12.5", "0.001", "5.0"); empty when the text is not a number.
std::string canonical_decimal(std::string_view t);

/// The dictionary bound as written by the curator (`text`), as a canonical xsd:decimal;
/// `value` is the bound as read, for the message when the text is not a decimal.
std::string bound_decimal(const std::string& text, double value, const std::string& what);

}  // namespace geotex::rdf_detail
