// The scheme of a dictionary: id, version, namespace, title, languages, creator, licence
// and date.

#include "annotation/detail/dictionary_checker.hpp"

namespace geotex::dictionary_detail {

void Checker::check_scheme(const Entry& e, Dictionary& out) {
    if (!expect(e, YNode::Kind::Map, "scheme",
                "a map with id, version, namespace, title and languages"))
        return;
    const auto entries = map_entries(e.second, kSchemeKeys, "in 'scheme'");
    for (const auto& key : kRequiredSchemeKeys)
        if (!entries.count(key)) missing(e.second, "scheme", key);
    if (entries.count("id") && text(entries.at("id"), "scheme.id", out.id) && !is_id(out.id))
        p_.add(node(entries.at("id").second).offset,
               "scheme.id " + quoted(out.id) +
                   " may hold only letters, digits, '-', '_' and '.' (it goes into IRIs)");
    if (entries.count("version")) text(entries.at("version"), "scheme.version", out.version);
    if (entries.count("namespace") &&
        text(entries.at("namespace"), "scheme.namespace", out.namespace_iri)) {
        const std::string why = namespace_problem(out.namespace_iri);
        if (!why.empty())
            p_.add(node(entries.at("namespace").second).offset,
                   "scheme.namespace " + quoted(out.namespace_iri) + " " + why);
    }
    if (entries.count("languages")) check_languages(entries.at("languages"), out);
    if (entries.count("title"))
        texts_by_language(entries.at("title"), "scheme.title", out.titles, false,
                          languages_ok_ ? &out.languages : nullptr);
    if (entries.count("creator"))
        iris(entries.at("creator"), "scheme.creator", out.creators,
             "an IRI or a list of IRIs (https://w3id.org/geotex/)");
    if (entries.count("license")) {
        std::vector<std::string> license;
        // One licence: a list would leave open which one applies.
        if (expect(entries.at("license"), YNode::Kind::Scalar, "scheme.license",
                   "one IRI (e.g. https://creativecommons.org/licenses/by/4.0/)"))
            iris(entries.at("license"), "scheme.license", license, "");
        if (!license.empty()) out.license = license.front();
    }
    if (entries.count("modified")) check_modified(entries.at("modified"), out);
}

void Checker::check_modified(const Entry& e, Dictionary& out) {
    std::string value;
    if (!text(e, "scheme.modified", value)) return;
    if (!is_calendar_date(value)) {
        p_.add(node(e.second).offset,
               "scheme.modified " + quoted(value) +
                   " is not a date: write the day this version was made as YYYY-MM-DD "
                   "(e.g. 2026-12-01)");
        return;
    }
    out.modified = value;
}

void Checker::check_languages(const Entry& e, Dictionary& out) {
    if (!expect(e, YNode::Kind::Sequence, "scheme.languages", "a list of language tags ([en, fr])"))
        return;
    const YNode& list = node(e.second);
    bool ok = true;
    if (list.items.empty()) {
        p_.add(list.offset, "scheme.languages is empty: list at least one language tag");
        ok = false;
    }
    for (int item : list.items) {
        const YNode& v = node(item);
        if (v.kind != YNode::Kind::Scalar || !is_language_tag(v.value)) {
            p_.add(v.offset, "scheme.languages: " +
                                 (v.kind == YNode::Kind::Scalar ? quoted(v.value)
                                                                : std::string(kind_name(v.kind))) +
                                 " is not a language tag (e.g. en, fr, pt-BR)");
            ok = false;
        } else if (std::find(out.languages.begin(), out.languages.end(), v.value) !=
                   out.languages.end()) {
            p_.add(v.offset, "scheme.languages lists " + quoted(v.value) + " twice");
        } else {
            out.languages.push_back(v.value);
        }
    }
    languages_ok_ = ok;
    languages_ = out.languages;
}

}  // namespace geotex::dictionary_detail
