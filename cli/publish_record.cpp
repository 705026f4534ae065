#include "cli/publish_record.hpp"

#include <filesystem>
#include <nlohmann/json.hpp>
#include <ostream>

#include "cli/dictionary_input.hpp"
#include "cli/output.hpp"

namespace geotex::cli {

namespace {
constexpr int kRecordSchema = 1;
}

PublishRecord read_publish_record(const std::string& path) {
    PublishRecord record;
    std::error_code ec;
    const auto status = std::filesystem::symlink_status(path, ec);
    if (!std::filesystem::exists(status)) return record;
    // Inside OUTDIR geotex follows no link it did not make, and a FIFO there would block the
    // read (even of a dry run).
    if (std::filesystem::is_symlink(status))
        throw CliError(kExitOutput,
                       path + ": is a symbolic link, not followed inside an output directory");
    if (!std::filesystem::is_regular_file(status))
        throw CliError(kExitOutput, path + ": is not a regular file");
    const std::string text = read_text_file(path);
    const auto fail = [&](const std::string& what) {
        throw CliError(kExitInput, path + ": " + what + " (remove it to publish everything again)");
    };
    try {
        const nlohmann::json j = nlohmann::json::parse(text);
        const nlohmann::json& stamp = j.at("geotex");
        if (stamp.at("document").get<std::string>() != "published")
            fail("not a publish record (\"geotex.document\" is not \"published\")");
        if (stamp.at("schema").get<int>() != kRecordSchema)
            fail("record schema " + std::to_string(stamp.at("schema").get<int>()) +
                 "; this geotex reads schema " + std::to_string(kRecordSchema));
        for (const auto& [endpoint, graphs] : j.at("endpoints").items()) {
            auto& e = record.endpoints[endpoint];
            for (const auto& [graph, objects] : graphs.items()) {
                auto& g = e[graph];
                for (const auto& [id, o] : objects.items()) {
                    PublishedObject p;
                    p.annotation_sha256 = o.at("annotation_sha256").get<std::string>();
                    p.triples = o.at("triples").get<std::size_t>();
                    p.bytes = o.at("bytes").get<std::size_t>();
                    const std::string state = o.at("state").get<std::string>();
                    if (state != "sent" && state != "sending")
                        fail("object '" + id + "': unknown state '" + state + "'");
                    p.complete = state == "sent";
                    g[id] = p;
                }
            }
        }
    } catch (const nlohmann::json::exception& e) {
        fail(std::string("not a valid publish record: ") + e.what());
    }
    return record;
}

void write_publish_record(const std::string& path, const PublishRecord& record) {
    nlohmann::ordered_json j;
    j["geotex"] = {
        {"version", GEOTEX_VERSION}, {"document", "published"}, {"schema", kRecordSchema}};
    nlohmann::ordered_json endpoints = nlohmann::ordered_json::object();
    for (const auto& [endpoint, graphs] : record.endpoints) {
        nlohmann::ordered_json g = nlohmann::ordered_json::object();
        for (const auto& [graph, objects] : graphs) {
            if (objects.empty()) continue;
            nlohmann::ordered_json o = nlohmann::ordered_json::object();
            for (const auto& [id, p] : objects)
                o[id] = {{"annotation_sha256", p.annotation_sha256},
                         {"triples", p.triples},
                         {"bytes", p.bytes},
                         {"state", p.complete ? "sent" : "sending"}};
            g[graph] = std::move(o);
        }
        if (!g.empty()) endpoints[endpoint] = std::move(g);
    }
    j["endpoints"] = std::move(endpoints);
    OutputSet out(OutputLinks::Refuse);  // inside OUTDIR
    out.add(path, [&](std::ostream& s) { s << j.dump(2) << '\n'; });
    out.commit();
}

}  // namespace geotex::cli
