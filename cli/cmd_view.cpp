// geotex view: the curator's workbench, a single-page application served on 127.0.0.1 over
// the objects of a batch output directory (view/README.md). The only source that includes
// httplib.h; what it serves is made by the server-free core in view/.
//
// Registered in cli/commands.hpp as
//   Runner add_view(CLI::App& app);

#include <netinet/in.h>
#include <pthread.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "annotation/dictionary_edit.hpp"
#include "annotation/dictionary_fit.hpp"
#include "cli/commands.hpp"
#include "cli/dictionary_input.hpp"
#include "cli/output.hpp"
#include "cli/view_objects.hpp"
#include "common/errors.hpp"
#include "default_dictionary.hpp"
#include "geometry/mesh_io.hpp"
#include "pipeline/loaded_collection.hpp"
#include "view/api_json.hpp"
#include "view/assets.hpp"
#include "view/security.hpp"

// Last: httplib.h brings <resolv.h>, whose macro _res breaks Eigen's headers included after it.
#include <httplib.h>

namespace geotex::cli {

namespace {

using Json = nlohmann::json;

constexpr int kDefaultPort = 8765;
constexpr const char* kTokenCookie = "geotex_token";

struct ViewCliOptions {
    std::string path;
    std::string dictionary;
    int port = kDefaultPort;
    std::string host;
};

// What every request handler shares. The collection is read once at start and never
// changes; the dictionary, and the words it gives, change with each save, under `mutex`.
struct ViewState {
    LoadedCollection collection;
    std::vector<FitObject> fit_objects;  // what fit_dictionary reads of the collection
    view::AccessPolicy policy;
    std::string dictionary_file;  // --dictionary FILE, "" for the built-in default
    std::mutex mutex;
    std::string dictionary_text;  // as last saved: the text every edit applies to
    std::shared_ptr<const Dictionary> dictionary;
    std::vector<ObjectWords> words;  // every object's words under `dictionary`
    // The meshes and thumbnails, made from the objects' segmentations.
    ViewObjects objects{collection};

    std::shared_ptr<const Dictionary> current_dictionary() {
        const std::lock_guard<std::mutex> lock(mutex);
        return dictionary;
    }
};

// Sends `body` as it is (httplib compresses set_content bodies of text types when the client
// accepts it, and brotli takes seconds over three.js, but never a content provider's); then
// runs `after`, if given, on the same worker once the response is written or abandoned: httplib
// calls a content provider's releaser when the response ends. `after` is work that may be skipped:
// an exception from it is dropped there, as nothing could report it any more.
void send_then(httplib::Response& res, std::shared_ptr<const std::string> body,
               const std::string& type, std::function<void()> after) {
    const std::size_t size = body->size();
    auto provider = [body](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
        return sink.write(body->data() + offset, length);
    };
    if (!after) return res.set_content_provider(size, type, std::move(provider));
    // Once: a copy of the Response would call the releaser again.
    auto once = std::make_shared<std::once_flag>();
    res.set_content_provider(size, type, std::move(provider),
                             [once, after = std::move(after)](bool) {
                                 std::call_once(*once, [&] {
                                     try {
                                         after();
                                     } catch (...) {
                                     }
                                 });
                             });
}

void send(httplib::Response& res, std::shared_ptr<const std::string> body,
          const std::string& type) {
    send_then(res, std::move(body), type, nullptr);
}

void send_json(httplib::Response& res, const Json& body, int status = 200) {
    res.status = status;
    send(res,
         std::make_shared<const std::string>(
             body.dump(-1, ' ', false, Json::error_handler_t::replace)),
         "application/json");
}

void send_error(httplib::Response& res, int status, const std::string& message) {
    send_json(res, view::error_json(message), status);
}

std::optional<std::string> header(const httplib::Request& req, const char* name) {
    if (!req.has_header(name)) return std::nullopt;
    return req.get_header_value(name);
}

view::RequestFacts facts_of(const httplib::Request& req) {
    view::RequestFacts f;
    f.method = req.method;
    f.host = header(req, "Host");
    f.origin = header(req, "Origin");
    f.header_token = header(req, "X-Geotex-Token");
    if (req.has_param("token")) f.query_token = req.get_param_value("token");
    if (const auto cookie = header(req, "Cookie"))
        f.cookie_token = view::cookie_value(*cookie, kTokenCookie);
    return f;
}

// The object a route names, or nullptr after answering 404.
const LoadedObject* object_of(ViewState& state, const httplib::Request& req,
                              httplib::Response& res) {
    const std::string id = req.matches[1];
    const LoadedObject* o = view::find_object(state.collection, id);
    if (o == nullptr)
        send_error(res, 404,
                   "no object '" + id + "' in " + view::collection_name(state.collection));
    return o;
}

// The segmentation of an object, or nullptr after answering with the error of a missing or
// corrupt file.
std::unique_ptr<MeshFile> segmentation_of(ViewState& state, const LoadedObject& o,
                                          httplib::Response& res) {
    if (!o.error.empty()) {
        send_error(res, 404, o.id + ": " + o.error);
        return nullptr;
    }
    try {
        return state.objects.read_segmentation(o);
    } catch (const Error& e) {
        send_error(res, 422, e.located(state.objects.segmentation_path(o)));
        return nullptr;
    }
}

// GET of an object's mesh or thumbnail. Both come from one reading of the segmentation:
// whichever is asked first makes the other once its own answer is sent, still holding the
// object's reader, so the object a curator opens from the list finds its mesh made while the
// list showed its thumbnail. A failure of the other one is left for its own request to report.
httplib::Server::Handler serve_product(ViewState& state, ViewObjects::Product what,
                                       const char* type) {
    return [&state, what, type](const httplib::Request& req, httplib::Response& res) {
        const LoadedObject* o = object_of(state, req, res);
        if (o == nullptr) return;
        ViewObjects& objects = state.objects;
        if (auto held = objects.held(what, o->id)) return send(res, held, type);
        auto reading = std::make_shared<std::unique_lock<std::mutex>>(*objects.reader_of(o->id));
        if (auto held = objects.held(what, o->id)) return send(res, held, type);
        std::shared_ptr<const MeshFile> file = segmentation_of(state, *o, res);
        if (!file) return;
        std::shared_ptr<const std::string> made;
        try {
            made = objects.make(what, *file, *o);
        } catch (const Error& e) {
            return send_error(res, 422, e.located());
        }
        objects.keep(what, o->id, made);
        const auto other = what == ViewObjects::Product::Mesh ? ViewObjects::Product::Thumbnail
                                                              : ViewObjects::Product::Mesh;
        send_then(res, made, type, [&objects, o, file, reading, other] {
            if (!objects.held(other, o->id))
                objects.keep(other, o->id, objects.make(other, *file, *o));
        });
    };
}

void add_routes(httplib::Server& server, ViewState& state) {
    server.Get("/", [&state](const httplib::Request& req, httplib::Response& res) {
        const view::EmbeddedAsset* index = view::find_asset("index.html");
        if (index == nullptr) return send_error(res, 404, "this geotex was built without its page");
        if (state.policy.custom_host)
            // With --host, the token of the first load (?token=) is kept in a cookie that the
            // page's own requests (scripts, images) carry; SameSite=Strict keeps it off every
            // request another site makes.
            res.set_header("Set-Cookie", std::string(kTokenCookie) + "=" + state.policy.token +
                                             "; Path=/; HttpOnly; SameSite=Strict");
        (void)req;
        send(
            res,
            std::make_shared<const std::string>(view::fill_token(index->bytes, state.policy.token)),
            view::content_type_of("index.html"));
    });
    server.Get(R"(/assets/([^/]+))", [](const httplib::Request& req, httplib::Response& res) {
        const std::string name = req.matches[1];
        const view::EmbeddedAsset* asset = view::find_asset(name);
        if (asset == nullptr || name == "index.html")
            return send_error(res, 404, "no asset '" + name + "'");
        // The bytes live in the binary for the whole run: no copy.
        const std::string_view bytes = asset->bytes;
        res.set_content_provider(
            bytes.size(), view::content_type_of(name),
            [bytes](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
                return sink.write(bytes.data() + offset, length);
            });
        res.set_header("Cache-Control", "no-cache");
    });
    server.Get("/api/session", [&state](const httplib::Request&, httplib::Response& res) {
        const auto dictionary = state.current_dictionary();
        view::DictionaryInUse in_use{dictionary.get(), state.dictionary_file,
                                     !state.dictionary_file.empty()};
        Json session = view::session_json(state.collection, in_use);
        session["meshes_ready"] = state.objects.held_meshes();
        session["preparing"] = state.objects.preparing();
        send_json(res, session);
    });
    server.Get("/api/objects", [&state](const httplib::Request&, httplib::Response& res) {
        send_json(res, view::objects_json(state.collection));
    });
    server.Get("/api/features", [&state](const httplib::Request&, httplib::Response& res) {
        send_json(res, view::features_json(state.collection));
    });
    server.Get("/api/dictionary", [&state](const httplib::Request&, httplib::Response& res) {
        std::string text;
        std::shared_ptr<const Dictionary> dictionary;
        {
            const std::lock_guard<std::mutex> lock(state.mutex);
            text = state.dictionary_text;
            dictionary = state.dictionary;
        }
        send_json(res, Json{{"text", text},
                            {"concepts", view::concepts_json(*dictionary)},
                            {"problems", view::problems_json(check_dictionary(text))["problems"]}});
    });
    server.Get(R"(/api/objects/([^/]+))",
               [&state](const httplib::Request& req, httplib::Response& res) {
                   const LoadedObject* o = object_of(state, req, res);
                   if (o == nullptr) return;
                   send_json(res, view::object_json(*o, *state.current_dictionary()));
               });
    server.Get(R"(/api/objects/([^/]+)/mesh)",
               serve_product(state, ViewObjects::Product::Mesh, "application/octet-stream"));
    server.Get(R"(/api/objects/([^/]+)/thumbnail\.png)",
               serve_product(state, ViewObjects::Product::Thumbnail, "image/png"));
}

// The body of a POST as JSON, or nullopt after answering 400.
std::optional<Json> body_of(const httplib::Request& req, httplib::Response& res) {
    Json body = Json::parse(req.body, nullptr, false);
    if (body.is_discarded() || !body.is_object()) {
        send_error(res, 400, "the body is not a JSON object");
        return std::nullopt;
    }
    return body;
}

// The dictionary that edits make of the text as last saved, or the problems of the edits and
// of the text they make (edit_dictionary then check_dictionary).
struct EditedDictionary {
    std::string text;
    std::shared_ptr<const Dictionary> dictionary;  // null when there are problems
    std::vector<DictionaryProblem> problems;
};

EditedDictionary apply_edits(const std::string& text, const std::vector<DictionaryEdit>& edits,
                             const std::string& name) {
    DictionaryEditResult r = edit_dictionary(text, edits);
    EditedDictionary out{std::move(r.text), nullptr, std::move(r.problems)};
    if (out.problems.empty())
        out.dictionary = std::make_shared<const Dictionary>(parse_dictionary(out.text, name));
    return out;
}

// The edits of a POST body, or nullopt after answering 400.
std::optional<std::vector<DictionaryEdit>> edits_of(const Json& body, httplib::Response& res) {
    try {
        return view::edits_from_json(body.contains("edits") ? body["edits"] : Json::array());
    } catch (const Error& e) {
        send_error(res, 400, e.what());
        return std::nullopt;
    }
}

std::string dictionary_name(const ViewState& state) {
    return state.dictionary_file.empty() ? std::string(kDefaultDictionaryName)
                                         : state.dictionary_file;
}

void add_edit_routes(httplib::Server& server, ViewState& state) {
    server.Post("/api/preview", [&state](const httplib::Request& req, httplib::Response& res) {
        const auto body = body_of(req, res);
        if (!body) return;
        const auto edits = edits_of(*body, res);
        if (!edits) return;
        std::string text;
        std::vector<ObjectWords> before;
        {
            const std::lock_guard<std::mutex> lock(state.mutex);
            text = state.dictionary_text;
            before = state.words;
        }
        const EditedDictionary edited = apply_edits(text, *edits, dictionary_name(state));
        if (!edited.problems.empty())
            return send_json(res, view::problems_json(edited.problems), 422);
        const auto descriptions = reannotate(state.collection, *edited.dictionary);
        const auto changes = diff_words(state.collection, before, chosen_words(descriptions));
        Json objects = Json::array();
        for (std::size_t i = 0; i < state.collection.objects.size(); ++i) {
            const LoadedObject& o = state.collection.objects[i];
            if (!o.reannotate) continue;
            objects.push_back(
                Json{{"id", o.id},
                     {"textures", view::textures_json(o, *edited.dictionary,
                                                      view::annotation_json(descriptions[i]))}});
        }
        Json changed = Json::array();
        for (const WordChange& c : changes)
            changed.push_back(Json{{"object", c.object},
                                   {"texture", c.texture},
                                   {"before", c.before},
                                   {"after", c.after}});
        send_json(res, Json{{"concepts", view::concepts_json(*edited.dictionary)},
                            {"objects", objects},
                            {"changed", changed}});
    });
    server.Post("/api/save", [&state](const httplib::Request& req, httplib::Response& res) {
        if (state.dictionary_file.empty())
            return send_error(res, 409,
                              "no --dictionary FILE was given: the built-in dictionary is "
                              "read-only");
        const auto body = body_of(req, res);
        if (!body) return;
        const auto edits = edits_of(*body, res);
        if (!edits) return;
        // One save at a time, each on the text the one before wrote.
        static std::mutex saving;
        const std::lock_guard<std::mutex> one_save(saving);
        std::string text;
        {
            const std::lock_guard<std::mutex> lock(state.mutex);
            text = state.dictionary_text;
        }
        // The curator may have edited FILE in a text editor meanwhile: writing the workbench's
        // text over it would lose that work without a word.
        std::string on_disk;
        try {
            on_disk = read_text_file(state.dictionary_file);
        } catch (const Error& e) {
            return send_error(res, 409, e.located() + "; nothing was saved");
        }
        if (on_disk != text)
            return send_error(res, 409,
                              state.dictionary_file +
                                  ": changed on disk since geotex view read it; nothing was "
                                  "saved (restart geotex view to edit the new text)");
        EditedDictionary edited = apply_edits(text, *edits, state.dictionary_file);
        if (!edited.problems.empty())
            return send_json(res, view::problems_json(edited.problems), 422);
        const std::string stamped = stamp_new_version(edited.text, version_date());
        const EditedDictionary saved = apply_edits(stamped, {}, state.dictionary_file);
        if (!saved.problems.empty())
            return send_json(res, view::problems_json(saved.problems), 422);
        try {
            OutputSet out(OutputLinks::Follow);
            out.add(state.dictionary_file, [&](std::ostream& os) { os << stamped; });
            out.commit();
        } catch (const CliError& e) {
            return send_error(res, 500, e.what());
        }
        auto words = chosen_words(reannotate(state.collection, *saved.dictionary));
        {
            const std::lock_guard<std::mutex> lock(state.mutex);
            state.dictionary_text = stamped;
            state.dictionary = saved.dictionary;
            state.words = std::move(words);
        }
        send_json(res, Json{{"version", saved.dictionary->version},
                            {"sha256", saved.dictionary->sha256}});
    });
    server.Post("/api/fit", [&state](const httplib::Request& req, httplib::Response& res) {
        const auto body = body_of(req, res);
        if (!body) return;
        std::vector<FitMark> marks;
        try {
            marks = view::marks_from_json(*body);
        } catch (const Error& e) {
            return send_error(res, 400, e.what());
        }
        send_json(res, view::fit_json(
                           fit_dictionary(*state.current_dictionary(), state.fit_objects, marks)));
    });
}

// Every request passes the Host, Origin and token checks first (view/README.md, Security).
void add_checks(httplib::Server& server, ViewState& state) {
    server.set_pre_routing_handler([&state](const httplib::Request& req, httplib::Response& res) {
        const std::string refusal = view::check_request(facts_of(req), state.policy);
        if (refusal.empty()) return httplib::Server::HandlerResponse::Unhandled;
        send_error(res, 403, refusal);
        return httplib::Server::HandlerResponse::Handled;
    });
    // A route that answers nothing (no such route: 404) still answers in JSON.
    server.set_error_handler(httplib::Server::HandlerWithResponse(
        [](const httplib::Request& req, httplib::Response& res) {
            if (!res.body.empty() || res.content_provider_)
                return httplib::Server::HandlerResponse::Unhandled;
            send_json(res,
                      view::error_json(res.status == 404 ? "no route " + req.method + " " + req.path
                                                         : "request refused"),
                      res.status);
            return httplib::Server::HandlerResponse::Handled;
        }));
    server.set_exception_handler(
        [](const httplib::Request&, httplib::Response& res, std::exception_ptr error) {
            std::string what = "internal error";
            try {
                std::rethrow_exception(error);
            } catch (const Error& e) {
                what = e.located();
            } catch (const std::exception& e) {
                what = std::string("internal error: ") + e.what();
            } catch (...) {
            }
            send_error(res, 500, what);
        });
}

// A socket that a second server cannot share: httplib's default options add SO_REUSEPORT,
// which lets two servers listen on one port and hides "port in use".
void reuse_address_only(socket_t sock) {
    const int yes = 1;
    ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
}

int run_view(const ViewCliOptions& o) {
    // SIGINT and SIGTERM are waited for by this thread alone (sigwait below): blocked here,
    // before the server starts its threads, they are blocked in every thread it starts.
    sigset_t stop_signals;
    sigemptyset(&stop_signals);
    sigaddset(&stop_signals, SIGINT);
    sigaddset(&stop_signals, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);

    auto state = std::make_unique<ViewState>();
    state->dictionary_file = o.dictionary;
    DictionarySource source = load_dictionary_source(o.dictionary);
    state->dictionary_text = std::move(source.text);
    state->dictionary = std::make_shared<const Dictionary>(std::move(source.dictionary));
    try {
        state->collection = load_collection(o.path);
    } catch (const Error& e) {
        throw CliError(kExitInput, "view: " + e.located(o.path));
    }
    state->fit_objects = fit_objects(state->collection);
    // The words of the dictionary as it is: what a preview's words are compared with.
    state->words = chosen_words(reannotate(state->collection, *state->dictionary));

    httplib::Server server;
    server.set_socket_options(reuse_address_only);
    server.set_keep_alive_timeout(2);
    // The largest body the page sends is a list of edits or marks: far below this.
    server.set_payload_max_length(std::size_t(16) << 20);
    add_checks(server, *state);
    add_routes(server, *state);
    add_edit_routes(server, *state);

    const std::string host = o.host.empty() ? std::string("127.0.0.1") : o.host;
    errno = 0;
    int port = o.port;
    const bool bound = o.port == 0 ? (port = server.bind_to_any_port(host)) > 0
                                   : server.bind_to_port(host, o.port);
    if (!bound) {
        const int why = errno;
        throw CliError(kExitUsage, "view: cannot listen on " + host + ":" + std::to_string(o.port) +
                                       (why != 0 ? std::string(" (") + std::strerror(why) + ")"
                                                 : std::string(" (in use, or no such address)")));
    }
    state->policy.listen_host = host;
    state->policy.custom_host = !o.host.empty();
    state->policy.port = port;
    state->policy.token = view::make_token();

    std::string url = "http://" + (o.host.empty() ? std::string("127.0.0.1") : host) + ":" +
                      std::to_string(port) + "/";
    if (state->policy.custom_host) url += "?token=" + state->policy.token;
    std::printf("geotex view: %s\n", url.c_str());
    std::fflush(stdout);

    std::atomic<bool> stop_preparing{false};
    std::thread preparing([&] { state->objects.prepare_first_objects(stop_preparing); });

    bool stopping = false;
    std::thread serving([&] {
        server.listen_after_bind();
        // The server ended by itself (not through stop()): wake the waiting main thread.
        if (!stopping) ::kill(::getpid(), SIGTERM);
    });
    int signal_number = 0;
    sigwait(&stop_signals, &signal_number);
    stopping = true;
    stop_preparing = true;
    server.stop();
    serving.join();
    preparing.join();
    return 0;
}

}  // namespace

Runner add_view(CLI::App& app) {
    auto o = std::make_shared<ViewCliOptions>();
    app.description(
        "Serve the curator's workbench for a batch output directory (or one object's outputs) on\n"
        "http://127.0.0.1:PORT/: the objects with their textures and words in 3D, the features'\n"
        "histograms with the dictionary's bounds, dictionary edits previewed on every object and\n"
        "saved to --dictionary FILE. Ctrl-C stops it.");
    app.add_option("PATH", o->path,
                   "A geotex batch output directory (summary.csv, objects/<id>/), or a directory "
                   "holding one object's report.json and segmentation.ply")
        ->required();
    app.add_option("--dictionary", o->dictionary,
                   "The YAML dictionary the curator edits (the batch's --dictionary); saving "
                   "writes it, atomically. Without it the built-in default is shown read-only")
        ->check(CLI::ExistingFile);
    app.add_option("--port", o->port,
                   "Port to listen on; 0 picks a free one (printed). A port in use is an error")
        ->check(CLI::Range(0, 65535))
        ->capture_default_str();
    app.add_option("--host", o->host,
                   "Listen on this address instead of 127.0.0.1; then every request needs the "
                   "token printed in the URL (?token=...)")
        ->type_name("ADDR")
        // An empty value would otherwise read as "not given" and listen on 127.0.0.1 without
        // the token the user asked for by naming a host.
        ->check([](const std::string& v) { return v.empty() ? "an empty address" : ""; });
    app.footer(
        "Security: only 127.0.0.1 by default; every request's Host and Origin must name this\n"
        "server (against DNS rebinding and other sites' pages), every POST carries the run's\n"
        "token, and only PATH's summaries and objects' outputs are read, never through a link.\n"
        "The page, three.js included, is built into geotex: it works offline.");
    return [o] { return run_view(*o); };
}

}  // namespace geotex::cli
