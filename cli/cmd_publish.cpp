// geotex publish: the complete objects of a batch output directory into a triple store
// (SPARQL 1.1 Graph Store HTTP Protocol) and/or one N-Quads file for a bulk loader.

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <set>
#include <string>
#include <vector>

#include "cli/batch_objects.hpp"
#include "cli/commands.hpp"
#include "cli/graph_store.hpp"
#include "cli/output.hpp"
#include "cli/publish_record.hpp"
#include "common/errors.hpp"
#include "ontology/rdf_transcode.hpp"
#include "ontology/rdf_writer.hpp"

namespace geotex::cli {

namespace {

constexpr const char* kPasswordVariable = "GEOTEX_STORE_PASSWORD";

struct PublishOptions {
    CommonOptions common;
    std::string outdir;
    std::string endpoint;
    bool graph_per_object = false;
    std::string graph;
    std::string nquads;
    bool dry_run = false;
    bool force = false;
    std::size_t chunk_triples = 100000;
    GraphStoreSettings store;
};

enum class Status { Sent, Unchanged, Failed, Skipped, WouldSend };

const char* status_name(Status s) {
    switch (s) {
        case Status::Sent:
            return "sent";
        case Status::Unchanged:
            return "unchanged";
        case Status::Failed:
            return "failed";
        case Status::Skipped:
            return "skipped";
        case Status::WouldSend:
            return "would-send";
    }
    return "";
}

/// One object's line of the report, and what is planned for it.
struct Item {
    std::string id;
    const BatchObject* object = nullptr;  ///< null: incomplete (skipped)
    std::string graph;
    Status status = Status::Skipped;
    bool send = false;      ///< planned: send its triples
    bool replaces = false;  ///< its first request is a PUT (the graph is replaced)
    std::size_t triples = 0;
    std::size_t bytes = 0;
    int requests = 0;
    double seconds = 0;
    std::string reason;
};

/// RFC 4180 field.
std::string csv_field(const std::string& s) {
    if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
    std::string out = "\"";
    for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

void print_item(const Item& item) {
    std::printf("%-10s %9zu triples %11zu bytes %7.2f s  %s%s\n", status_name(item.status),
                item.triples, item.bytes, item.seconds, item.id.c_str(),
                item.reason.empty() ? "" : ("  (" + item.reason + ")").c_str());
}

void write_report_csv(const std::string& path, const std::vector<Item>& items) {
    OutputSet out(OutputLinks::Refuse);  // inside OUTDIR
    out.add(path, [&](std::ostream& s) {
        s << "id,graph,status,triples,bytes,requests,seconds,reason\r\n";
        for (const Item& i : items) {
            char seconds[32];
            std::snprintf(seconds, sizeof seconds, "%.3f", i.seconds);
            s << csv_field(i.id) << ',' << csv_field(i.graph) << ',' << status_name(i.status) << ','
              << i.triples << ',' << i.bytes << ',' << i.requests << ',' << seconds << ','
              << csv_field(i.reason) << "\r\n";
        }
    });
    out.commit();
}

/// The graph an object's triples go to.
std::string graph_of(const PublishOptions& o, const BatchObject& object) {
    return o.graph.empty() ? object.graph : o.graph;
}

/// --nquads: every complete object in its graph, one file, all or nothing. Returns false
/// when an object could not be written (it is left out, with an error line).
bool write_nquads_file(const PublishOptions& o, const BatchObjects& objects, Progress& progress) {
    bool all = true;
    std::size_t num_quads = 0, num_objects = 0;
    OutputSet out;
    timed_stage(progress, "N-Quads", [&] {
        out.add(o.nquads, [&](std::ostream& s) {
            NQuadsWriter writer(s);
            for (const BatchObject& object : objects.complete) {
                std::string reason;
                const std::optional<std::string> text = read_verified_annotation(object, reason);
                try {
                    if (!text) throw InvalidInput(reason);
                    num_quads += writer.add(*text, object.annotation_path, graph_of(o, object));
                    ++num_objects;
                } catch (const ParseError& e) {
                    std::fprintf(stderr, "geotex: error: %s: left out of %s\n", e.located().c_str(),
                                 o.nquads.c_str());
                    all = false;
                } catch (const InvalidInput& e) {
                    std::fprintf(stderr, "geotex: error: %s: %s; left out of %s\n",
                                 object.dir.c_str(), e.what(), o.nquads.c_str());
                    all = false;
                }
            }
            writer.finish();
        });
        out.commit();
    });
    std::printf("wrote %s: %zu objects, %zu quads\n", o.nquads.c_str(), num_objects, num_quads);
    return all;
}

/// The Graph Store side: plans every object against published.json, sends, keeps the record
/// up to date, prints and writes the report. Returns false when anything failed.
class Publisher {
  public:
    Publisher(const PublishOptions& o, const BatchObjects& objects, Progress& progress)
        : o_(o), progress_(progress), record_path_(o.outdir + "/published.json") {
        // Items in id order, incomplete objects among them.
        auto c = objects.complete.begin();
        auto i = objects.incomplete.begin();
        while (c != objects.complete.end() || i != objects.incomplete.end()) {
            Item item;
            if (i == objects.incomplete.end() || (c != objects.complete.end() && c->id < i->id)) {
                item.id = c->id;
                item.object = &*c;
                item.graph = graph_of(o, *c);
                ++c;
            } else {
                item.id = i->id;
                item.status = Status::Skipped;
                item.reason = i->reason;
                ++i;
            }
            items_.push_back(std::move(item));
        }
        record_ = read_publish_record(record_path_);
    }

    bool run() {
        plan();
        std::size_t to_send = 0;
        for (const Item& i : items_) to_send += i.send;
        progress_.note(o_.store.endpoint + ": " + std::to_string(to_send) + " of " +
                       std::to_string(items_.size()) + " objects to send" +
                       (o_.graph.empty() ? ", one graph each" : " into <" + o_.graph + ">") +
                       (o_.dry_run ? " (dry run: nothing is sent)" : ""));
        if (!o_.dry_run)
            client_ = std::make_unique<GraphStoreClient>(
                o_.store, [this](const std::string& m) { progress_.note(current_ + ": " + m); });
        bool stopped = false;
        for (Item& item : items_) {
            if (item.send && stopped) {
                item.status = Status::Failed;
                item.reason = "not attempted: the endpoint failed";
            } else if (item.send) {
                stopped = !send(item);
            }
            print_item(item);
        }
        if (dirty_) write_publish_record(record_path_, record_);
        std::map<Status, int> count;
        for (const Item& i : items_) ++count[i.status];
        if (o_.dry_run) {
            std::printf("%s: %d would be sent, %d unchanged, %d failed, %d skipped (dry run)\n",
                        o_.store.endpoint.c_str(), count[Status::WouldSend],
                        count[Status::Unchanged], count[Status::Failed], count[Status::Skipped]);
            return count[Status::Failed] == 0;
        }
        write_report_csv(o_.outdir + "/publish-report.csv", items_);
        std::printf("%s: %d sent, %d unchanged, %d failed, %d skipped (report: %s)\n",
                    o_.store.endpoint.c_str(), count[Status::Sent], count[Status::Unchanged],
                    count[Status::Failed], count[Status::Skipped],
                    (o_.outdir + "/publish-report.csv").c_str());
        return count[Status::Failed] == 0;
    }

  private:
    std::map<std::string, PublishedGraph>& graphs() { return record_.endpoints[o_.store.endpoint]; }

    const PublishedGraph* recorded(const std::string& graph) {
        const auto e = record_.endpoints.find(o_.store.endpoint);
        if (e == record_.endpoints.end()) return nullptr;
        const auto g = e->second.find(graph);
        return g == e->second.end() ? nullptr : &g->second;
    }

    void mark_unchanged(Item& item, const PublishedObject& p) {
        item.status = Status::Unchanged;
        item.triples = p.triples;
        item.bytes = p.bytes;
    }

    void plan() {
        if (o_.graph.empty()) {
            // One graph per object; PUT replaces it, so an object is sent alone into it.
            std::map<std::string, std::string> owner;  // graph -> first object
            for (Item& item : items_) {
                if (!item.object) continue;
                const auto [it, fresh] = owner.emplace(item.graph, item.id);
                if (!fresh) {
                    item.status = Status::Failed;
                    item.reason = "its graph <" + item.graph + "> is also the graph of object '" +
                                  it->second + "'; give them distinct graphs, or use --graph";
                    std::fprintf(stderr, "geotex: error: %s: %s\n", item.object->dir.c_str(),
                                 item.reason.c_str());
                    continue;
                }
                const PublishedGraph* g = recorded(item.graph);
                const auto p = g ? g->find(item.id) : PublishedGraph::const_iterator();
                if (!o_.force && g && g->size() == 1 && p != g->end() && p->second.complete &&
                    p->second.annotation_sha256 == item.object->annotation_sha256) {
                    mark_unchanged(item, p->second);
                } else {
                    item.send = true;
                    item.replaces = true;
                }
            }
            return;
        }
        // One graph for the collection. Objects can only be added to it (POST); one that
        // changed or went away, or a send that did not finish, means rewriting the graph.
        const PublishedGraph* g = recorded(o_.graph);
        std::map<std::string, const BatchObject*> now;
        for (const Item& item : items_)
            if (item.object) now[item.id] = item.object;
        rewrite_ = o_.force || !g || g->empty();
        for (const auto& [id, p] : g ? *g : PublishedGraph()) {
            const auto n = now.find(id);
            if (!p.complete || n == now.end() ||
                n->second->annotation_sha256 != p.annotation_sha256)
                rewrite_ = true;
        }
        if (rewrite_ && g && !g->empty() && !o_.force)
            progress_.note("<" + o_.graph +
                           "> holds objects that changed, went away or were not "
                           "sent whole: the graph is rewritten");
        for (Item& item : items_) {
            if (!item.object) continue;
            if (!rewrite_) {
                const auto p = g->find(item.id);
                if (p != g->end()) {
                    mark_unchanged(item, p->second);
                    continue;
                }
            }
            item.send = true;
        }
    }

    /// Records that `item` is being sent (the graph's content unknown until it is done) and
    /// saves the record: in the same write as the success of the previous object.
    void mark_sending(const Item& item, bool replaces) {
        PublishedObject p;
        p.annotation_sha256 = item.object->annotation_sha256;
        p.complete = false;
        PublishedGraph& g = graphs()[item.graph];
        if (replaces) g.clear();
        g[item.id] = p;
        write_publish_record(record_path_, record_);
        dirty_ = false;
    }

    /// Sends one object; returns false when the endpoint failed in a way that every further
    /// request would meet too.
    bool send(Item& item) {
        current_ = item.id;
        const auto start = std::chrono::steady_clock::now();
        const auto elapsed = [&] {
            return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        };
        std::string reason;
        const std::optional<std::string> text = read_verified_annotation(*item.object, reason);
        if (!text) {
            item.status = Status::Failed;
            item.reason = reason;
            std::fprintf(stderr, "geotex: error: %s: %s\n", item.object->dir.c_str(),
                         reason.c_str());
            return true;
        }
        NTriplesChunks chunks;
        try {
            NTriplesChunkParams params;
            params.max_triples = o_.chunk_triples;
            chunks = make_ntriples_chunks(*text, item.object->annotation_path, params);
        } catch (const Error& e) {
            item.status = Status::Failed;
            item.reason = e.what();
            std::fprintf(stderr, "geotex: error: %s: not sent\n", e.located().c_str());
            return true;
        }
        item.triples = chunks.num_triples;
        // Small enough: the file as written, Turtle. Else N-Triples chunks: one upload of tens
        // of MB can hang a store (Virtuoso), and N-Triples can be cut anywhere between lines.
        const bool whole = chunks.chunks.size() <= 1;
        if (!whole && chunks.has_blank_nodes)
            warn(item.object->annotation_path + ": has blank nodes and is sent in " +
                 std::to_string(chunks.chunks.size()) +
                 " requests: a blank node of two requests becomes two nodes in the store");
        std::vector<std::string_view> bodies;
        if (whole)
            bodies.emplace_back(*text);
        else
            for (const std::string& c : chunks.chunks) bodies.emplace_back(c);
        const std::string type = whole ? "text/turtle" : "application/n-triples";
        const bool replaces = item.replaces || (rewrite_ && !graph_replaced_);
        for (const auto& b : bodies) item.bytes += b.size();
        item.requests = static_cast<int>(bodies.size());

        if (o_.dry_run) {
            item.status = Status::WouldSend;
            item.reason = std::string(replaces ? "PUT" : "POST") +
                          (bodies.size() > 1
                               ? " then POST, " + std::to_string(bodies.size()) + " requests of "
                               : " ") +
                          type + " to " + graph_store_url(o_.store.endpoint, item.graph);
            return true;
        }
        mark_sending(item, replaces);
        for (std::size_t k = 0; k < bodies.size(); ++k) {
            const HttpMethod method = k == 0 && replaces ? HttpMethod::Put : HttpMethod::Post;
            const GraphStoreReply reply = client_->send(method, item.graph, bodies[k], type);
            if (!reply.ok) {
                item.status = Status::Failed;
                item.seconds = elapsed();
                item.reason =
                    (method == HttpMethod::Put ? "PUT" : "POST") +
                    (bodies.size() > 1
                         ? " " + std::to_string(k + 1) + " of " + std::to_string(bodies.size())
                         : std::string()) +
                    ": " + reply.error +
                    (reply.attempts > 1 ? " (" + std::to_string(reply.attempts) + " attempts)"
                                        : std::string());
                const std::size_t left = sends_after(item);
                std::fprintf(
                    stderr, "geotex: error: %s: object '%s' (graph <%s>): %s%s\n",
                    o_.store.endpoint.c_str(), item.id.c_str(), item.graph.c_str(),
                    item.reason.c_str(),
                    reply.endpoint_failed && left > 0
                        ? ("; stopped, " + std::to_string(left) + " more objects not sent").c_str()
                        : "");
                return !reply.endpoint_failed;
            }
            if (method == HttpMethod::Put) graph_replaced_ = true;
        }
        PublishedObject& p = graphs()[item.graph][item.id];
        p.triples = item.triples;
        p.bytes = item.bytes;
        p.complete = true;
        dirty_ = true;
        // Saved now unless the next object's mark_sending saves it at once.
        if (sends_after(item) == 0) {
            write_publish_record(record_path_, record_);
            dirty_ = false;
        }
        item.status = Status::Sent;
        item.seconds = elapsed();
        return true;
    }

    /// Objects planned to be sent after `item`.
    std::size_t sends_after(const Item& item) const {
        std::size_t n = 0;
        for (const Item* i = &item + 1; i < items_.data() + items_.size(); ++i) n += i->send;
        return n;
    }

    const PublishOptions& o_;
    Progress& progress_;
    std::string record_path_;
    PublishRecord record_;
    std::vector<Item> items_;
    std::unique_ptr<GraphStoreClient> client_;
    std::string current_;          // the object being sent, for retry messages
    bool rewrite_ = false;         // one graph for all, rewritten from scratch
    bool graph_replaced_ = false;  // its PUT went through
    bool dirty_ = false;           // record_ holds a success not yet saved
};

/// Every file in the objects' directories (complete or not): what --nquads must not replace.
InputFiles object_files(const std::string& outdir, const BatchObjects& objects) {
    InputFiles files;
    std::vector<std::string> ids;
    for (const BatchObject& c : objects.complete) ids.push_back(c.id);
    for (const IncompleteObject& i : objects.incomplete) ids.push_back(i.id);
    for (const std::string& id : ids) {
        std::error_code ec;
        const std::filesystem::path dir = std::filesystem::path(outdir) / "objects" / id;
        for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end;
             it.increment(ec))
            files.add({"of object '" + id + "'", it->path().string()});
    }
    return files;
}

int run_publish(PublishOptions& o) {
    Progress progress(o.common.quiet);
    // Options first, so that a typo costs nothing.
    if (o.endpoint.empty() && o.nquads.empty())
        throw CliError(kExitUsage, "nothing to do: give --endpoint URL, --nquads FILE or both");
    if (!o.graph.empty() && o.graph_per_object)
        throw CliError(kExitUsage, "--graph and --graph-per-object exclude each other");
    if (!o.graph.empty())
        in_phase(kExitUsage, "--graph", [&] { return validate_iri(o.graph, "graph IRI"); });
    if (!o.endpoint.empty()) {
        if (o.graph.empty() && !o.graph_per_object)
            throw CliError(kExitUsage,
                           "--endpoint needs --graph-per-object (each object into the graph its "
                           "run.json names) or --graph IRI (the whole collection into one graph)");
        o.store.endpoint = checked_endpoint(o.endpoint);
        if (!o.store.password.empty() && o.store.user.empty())
            throw CliError(kExitUsage, "--password needs --user");
        if (!o.store.user.empty() && o.store.password.empty())
            if (const char* p = std::getenv(kPasswordVariable)) o.store.password = p;
    } else if (o.graph_per_object || !o.store.user.empty() || o.force) {
        // Harmless, but a sign that --endpoint was forgotten.
        warn("--graph-per-object, --user and --force apply to --endpoint only");
    }
    while (o.outdir.size() > 1 && o.outdir.back() == '/') o.outdir.pop_back();
    std::vector<OutputPath> outputs = {{"--nquads", o.nquads}};
    if (!o.endpoint.empty() && !o.dry_run) {
        outputs.push_back({"the publish record", o.outdir + "/published.json", false, true});
        outputs.push_back({"the publish report", o.outdir + "/publish-report.csv", false, true});
    }

    const BatchObjects objects = list_batch_objects(o.outdir);
    if (!o.dry_run) check_output_paths(outputs, object_files(o.outdir, objects));
    for (const IncompleteObject& i : objects.incomplete)
        warn(o.outdir + "/objects/" + i.id + ": skipped: " + i.reason);
    if (objects.complete.empty()) warn(o.outdir + ": no complete object to publish");

    bool ok = true;
    if (!o.nquads.empty()) {
        if (o.dry_run)
            std::printf("would write %s: %zu objects\n", o.nquads.c_str(), objects.complete.size());
        else
            ok = write_nquads_file(o, objects, progress) && ok;
    }
    if (!o.endpoint.empty()) {
        Publisher publisher(o, objects, progress);
        ok = publisher.run() && ok;
    }
    std::fflush(stdout);
    return ok ? 0 : kExitProcessing;
}

}  // namespace

Runner add_publish(CLI::App& sub) {
    auto o = std::make_shared<PublishOptions>();
    sub.option_defaults()->always_capture_default(true);
    sub.description(
        "Send the complete objects of a 'geotex batch' output directory (OUTDIR/objects/<id>/\n"
        "with a run.json whose annotation.ttl digest matches) to a triple store, and/or write\n"
        "them as one N-Quads file for a store's bulk loader. Objects go in id order.\n"
        "\n"
        "--endpoint speaks the SPARQL 1.1 Graph Store HTTP Protocol (e.g. Virtuoso's\n"
        "http://HOST:8890/sparql-graph-crud, or /sparql-graph-crud-auth with --user). With\n"
        "--graph-per-object each object replaces its graph (PUT to URL?graph=<run.json graph>);\n"
        "with --graph IRI the collection goes into one graph (PUT, then POST). A file of more\n"
        "than --chunk-triples triples is sent as N-Triples in several requests (PUT, then POST):\n"
        "one upload of tens of MB can hang a store. OUTDIR/published.json records what went\n"
        "where, so a rerun sends only new and changed objects (--force: everything);\n"
        "OUTDIR/publish-report.csv and one line per object on stdout report sent, unchanged,\n"
        "failed or skipped objects.\n"
        "\n"
        "Connection errors, timeouts and 5xx answers are retried (--retries, waiting\n"
        "--retry-delay, doubled each time), 4xx answers are not. A store that cannot be reached,\n"
        "or refuses every request (401, 403, 404, 405, 501), stops the run with one error. Exit\n"
        "code 3 when an object failed. The password may come from the environment variable\n"
        "GEOTEX_STORE_PASSWORD. See docs/collections.md, section Publishing.");
    sub.add_option("outdir", o->outdir, "Output directory of geotex batch")->required();
    sub.add_option("--endpoint", o->endpoint, "Graph Store HTTP Protocol URL (http or https)");
    sub.add_flag("--graph-per-object", o->graph_per_object,
                 "Each object into the named graph its run.json names (its base IRI)");
    sub.add_option("--graph", o->graph, "One named graph (absolute IRI) for the whole collection");
    sub.add_option(
        "--nquads", o->nquads,
        "Also (or only) write every complete object as N-Quads, in its graph (--graph if "
        "given), for a bulk loader");
    sub.add_flag("--dry-run", o->dry_run,
                 "Show what would be sent and where; send and write nothing");
    sub.add_flag("--force", o->force, "Send every object, even those published.json has as sent");
    sub.add_option("--chunk-triples", o->chunk_triples, "Largest number of triples in one request")
        ->check(CLI::Range(std::size_t{1}, std::size_t{100000000}));
    sub.add_option("--timeout", o->store.timeout, "Seconds allowed for one request")
        ->check(CLI::Range(0.001, 86400.0));
    sub.add_option("--retries", o->store.retries,
                   "Further attempts after a connection error, a timeout or a 5xx answer")
        ->check(CLI::Range(0, 100));
    sub.add_option("--retry-delay", o->store.retry_delay,
                   "Seconds before the first retry, doubled before each next one")
        ->check(CLI::Range(0.0, 3600.0));
    sub.add_option("--user", o->store.user, "User name for an endpoint that needs authentication");
    sub.add_option("--password", o->store.password,
                   "Password (visible to other users of the machine: prefer the environment "
                   "variable GEOTEX_STORE_PASSWORD)");
    sub.add_option("--auth", o->store.auth,
                   "HTTP authentication: basic, digest, or auto (what the server asks for)")
        ->check(CLI::IsMember({"auto", "basic", "digest"}));
    add_output_options(sub);
    add_common_options(sub, o->common);
    return [o] { return run_publish(*o); };
}

}  // namespace geotex::cli
