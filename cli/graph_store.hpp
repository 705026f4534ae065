#pragma once
// A client of the SPARQL 1.1 Graph Store HTTP Protocol (libcurl): PUT replaces a named
// graph, POST adds to it. For `geotex publish`.

#include <functional>
#include <memory>
#include <string>
#include <string_view>

namespace geotex::cli {

/// How to reach a Graph Store endpoint.
struct GraphStoreSettings {
    std::string endpoint;       ///< http(s) URL (checked_endpoint), e.g. .../sparql-graph-crud
    std::string user;           ///< empty: no authentication
    std::string password;       ///< with user
    std::string auth = "auto";  ///< "basic", "digest" or "auto" (what the server asks for)
    double timeout = 120;       ///< seconds for one request, upload and answer included
    int retries = 3;            ///< further attempts after a connection error, a timeout or 5xx
    double retry_delay = 1;     ///< seconds before the first retry, doubled before each next
};

/// The endpoint URL in normal form, checked: http or https, a host, no credentials (they go
/// to --user/--password so that they appear in no message or record), no fragment. Throws
/// CliError (usage) naming what is wrong.
std::string checked_endpoint(const std::string& url);

/// The URL of a graph's resource: endpoint?graph=<graph IRI, percent-encoded> (&graph=
/// when the endpoint has a query already).
std::string graph_store_url(const std::string& endpoint, const std::string& graph);

enum class HttpMethod { Put, Post };

/// The outcome of one request, after its retries.
struct GraphStoreReply {
    bool ok = false;               ///< the store answered 2xx
    long status = 0;               ///< HTTP status of the last attempt; 0 when none came
    std::string error;             ///< why it failed, one line: curl's message, or the status
                                   ///< with the start of the answer's text
    bool endpoint_failed = false;  ///< every request would fail the same way (no answer at
                                   ///< all, a redirect, 401, 403, 404, 405, 501, 505): the
                                   ///< caller should stop
    int attempts = 0;
};

/// One connection (kept alive between requests) to a Graph Store endpoint.
class GraphStoreClient {
  public:
    /// `on_retry` is told, before each wait, why and how long (for progress messages).
    explicit GraphStoreClient(GraphStoreSettings settings,
                              std::function<void(const std::string&)> on_retry = {});
    GraphStoreClient(const GraphStoreClient&) = delete;
    GraphStoreClient& operator=(const GraphStoreClient&) = delete;
    ~GraphStoreClient();

    /// Sends `body` to the graph's resource. Retries connection errors, timeouts and 5xx
    /// answers but 501 and 505 (PUT and POST of the same triples are idempotent: a graph is
    /// a set), never 4xx. Network and HTTP problems are in the reply; throws only CliError
    /// (processing) when libcurl cannot be set up.
    GraphStoreReply send(HttpMethod method, const std::string& graph, std::string_view body,
                         const std::string& content_type);

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace geotex::cli
