#include "common/detail/csv.hpp"

#include "common/errors.hpp"

namespace geotex::detail {

std::vector<CsvRow> parse_csv(std::string_view text, const std::string& file) {
    if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
    std::vector<CsvRow> rows;
    long line = 1;
    std::size_t i = 0;
    while (i < text.size()) {
        CsvRow row;
        row.line = line;
        bool blank = true;  // an empty line holds no field at all
        for (;;) {
            std::string field;
            if (i < text.size() && text[i] == '"') {
                const long opened = line;
                ++i;
                for (;;) {
                    if (i >= text.size())
                        throw ParseError("quoted field opened here is never closed", file, opened);
                    if (text[i] == '"') {
                        if (i + 1 < text.size() && text[i + 1] == '"') {
                            field += '"';
                            i += 2;
                            continue;
                        }
                        ++i;
                        break;
                    }
                    if (text[i] == '\n') ++line;
                    field += text[i++];
                }
                blank = false;
                if (i < text.size() && text[i] == '\r' && i + 1 < text.size() &&
                    text[i + 1] == '\n')
                    ++i;
                if (i < text.size() && text[i] != ',' && text[i] != '\n')
                    throw ParseError(
                        "text after a closing quote (write \"\" for a quote inside a quoted field)",
                        file, line);
            } else {
                while (i < text.size() && text[i] != ',' && text[i] != '\n') field += text[i++];
                if (!field.empty() && field.back() == '\r' && (i >= text.size() || text[i] == '\n'))
                    field.pop_back();
                if (!field.empty()) blank = false;
            }
            row.fields.push_back(std::move(field));
            if (i < text.size() && text[i] == ',') {
                blank = false;
                ++i;
                continue;
            }
            break;  // end of line or of text
        }
        if (i < text.size() && text[i] == '\n') {
            ++i;
            ++line;
        }
        if (!blank) rows.push_back(std::move(row));
    }
    return rows;
}

std::string csv_field(std::string_view field) {
    if (field.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(field);
    std::string out = "\"";
    for (char ch : field) {
        if (ch == '"') out += '"';
        out += ch;
    }
    return out + '"';
}

}  // namespace geotex::detail
