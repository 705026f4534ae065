#include "cli/graph_store.hpp"

#include <curl/curl.h>
#include <openssl/evp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <regex>
#include <thread>
#include <utility>

#include "cli/output.hpp"
#include "common/detail/c_handle.hpp"

namespace geotex::cli {

namespace {

template <auto Free>
using Deleter = detail::CDeleter<Free>;
using CurlUrl = std::unique_ptr<CURLU, Deleter<curl_url_cleanup>>;
using CurlEasy = std::unique_ptr<CURL, Deleter<curl_easy_cleanup>>;
using CurlList = std::unique_ptr<curl_slist, Deleter<curl_slist_free_all>>;

void global_init() {
    static std::once_flag once;
    std::call_once(once, [] {
        if (curl_global_init(CURL_GLOBAL_DEFAULT) != 0)
            throw CliError(kExitProcessing, "libcurl could not be initialised");
    });
}

std::string url_part(CURLU* url, CURLUPart part) {
    char* value = nullptr;
    if (curl_url_get(url, part, &value, 0) != CURLUE_OK || !value) return {};
    std::string out(value);
    curl_free(value);
    return out;
}

/// The text of an answer body for a one-line message: HTML markup dropped (Virtuoso
/// answers errors with an HTML page), white space collapsed, cut at 300 characters.
std::string body_excerpt(const std::string& body) {
    static const std::regex markup(
        R"(<!DOCTYPE[^>]*>|</?(html|head|title|body|h[1-6]|p|pre|xmp|div|span|br|hr|meta|code|b|i|em|strong|a|ul|ol|li|table|tr|td|th)\b[^>]*>)",
        std::regex::icase);
    std::string text = std::regex_replace(body, markup, " ");
    std::string out;
    for (char c : text) {
        const bool space = c == ' ' || c == '\t' || c == '\r' || c == '\n';
        if (space) {
            if (!out.empty() && out.back() != ' ') out += ' ';
        } else if (static_cast<unsigned char>(c) >= 0x20) {
            out += c;
        }
    }
    while (!out.empty() && out.back() == ' ') out.pop_back();
    if (out.size() > 300) out = out.substr(0, 300) + "...";
    return out;
}

/// The answer body with whatever may be a credential removed, before it goes into a
/// message, published.json or publish-report.csv: a store (or a proxy) that echoes the
/// request must not get the password written to disk. Removed: the password itself, the
/// Basic token made from it (and "user:password"), and on any line naming an authorisation
/// header, a cookie, a token, a key or a password, everything after that name.
std::string redact_credentials(std::string body, const GraphStoreSettings& settings) {
    const auto replace_all = [&body](const std::string& secret) {
        if (secret.size() < 3) return;  // shorter: would garble the text, and says little
        for (auto at = body.find(secret); at != std::string::npos; at = body.find(secret, at))
            body.replace(at, secret.size(), "[removed]");
    };
    if (!settings.user.empty() || !settings.password.empty()) {
        const std::string pair = settings.user + ":" + settings.password;
        std::string token(4 * ((pair.size() + 2) / 3) + 1, '\0');
        const int n = EVP_EncodeBlock(reinterpret_cast<unsigned char*>(token.data()),
                                      reinterpret_cast<const unsigned char*>(pair.data()),
                                      static_cast<int>(pair.size()));
        token.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
        replace_all(token);
        replace_all(pair);
        replace_all(settings.password);
    }
    static const std::regex named(
        R"((proxy-authorization|authorization|www-authenticate|set-cookie|cookie|x-api-key|api[-_]?key|access[-_]?token|auth[-_]?token|password|passwd|secret)[^\r\n]*)",
        std::regex::icase);
    static const std::regex scheme(
        R"(\b(basic|bearer|digest|negotiate|ntlm)\s+[A-Za-z0-9+/=._~-]{6,})", std::regex::icase);
    body = std::regex_replace(body, named, "$1: [removed]");
    return std::regex_replace(body, scheme, "$1 [removed]");
}

bool retryable(CURLcode code) {
    switch (code) {
        case CURLE_COULDNT_RESOLVE_HOST:
        case CURLE_COULDNT_CONNECT:
        case CURLE_OPERATION_TIMEDOUT:
        case CURLE_SEND_ERROR:
        case CURLE_RECV_ERROR:
        case CURLE_GOT_NOTHING:
        case CURLE_PARTIAL_FILE:
            return true;
        default:
            return false;
    }
}

}  // namespace

std::string checked_endpoint(const std::string& text) {
    const auto fail = [&](const std::string& what) {
        throw CliError(kExitUsage, "--endpoint '" + text.substr(0, 200) + "': " + what);
    };
    global_init();
    CurlUrl url(curl_url());
    if (!url) throw CliError(kExitProcessing, "libcurl: out of memory");
    const CURLUcode rc = curl_url_set(url.get(), CURLUPART_URL, text.c_str(), 0);
    if (rc != CURLUE_OK) fail(std::string("not a URL (") + curl_url_strerror(rc) + ")");
    const std::string scheme = url_part(url.get(), CURLUPART_SCHEME);
    if (scheme != "http" && scheme != "https")
        fail("the scheme must be http or https, not '" + scheme + "'");
    if (url_part(url.get(), CURLUPART_HOST).empty()) fail("no host");
    if (!url_part(url.get(), CURLUPART_USER).empty() ||
        !url_part(url.get(), CURLUPART_PASSWORD).empty())
        fail("credentials in the URL; give them with --user and --password instead");
    if (!url_part(url.get(), CURLUPART_FRAGMENT).empty()) fail("a URL with a #fragment");
    return url_part(url.get(), CURLUPART_URL);
}

struct GraphStoreClient::Impl {
    GraphStoreSettings settings;
    std::function<void(const std::string&)> on_retry;
    CurlEasy curl;
    char error_buffer[CURL_ERROR_SIZE] = {};
    std::string body;         // the answer, its first kilobytes
    std::string status_line;  // "HTTP/1.1 500 Request Failed"

    static size_t on_body(char* data, size_t size, size_t nmemb, void* user) {
        auto* self = static_cast<Impl*>(user);
        const size_t n = size * nmemb;
        if (self->body.size() < 8192)
            self->body.append(data, std::min(n, 8192 - self->body.size()));
        return n;
    }
    static size_t on_header(char* data, size_t size, size_t nmemb, void* user) {
        auto* self = static_cast<Impl*>(user);
        const size_t n = size * nmemb;
        if (n >= 5 && std::equal(data, data + 5, "HTTP/")) {
            self->status_line.assign(data, n);
            while (!self->status_line.empty() &&
                   (self->status_line.back() == '\n' || self->status_line.back() == '\r'))
                self->status_line.pop_back();
        }
        return n;
    }

    /// One attempt. Returns curl's code; the status is in `status`.
    CURLcode attempt(HttpMethod method, const std::string& url, std::string_view data,
                     const std::string& content_type, long& status) {
        CURL* h = curl.get();
        curl_easy_reset(h);
        body.clear();
        status_line.clear();
        error_buffer[0] = '\0';
        CurlList headers(curl_slist_append(nullptr, ("Content-Type: " + content_type).c_str()));
        // No "Expect: 100-continue" round trip: not every store answers it.
        if (headers) headers.reset(curl_slist_append(headers.release(), "Expect:"));
        if (!headers) return CURLE_OUT_OF_MEMORY;
        const auto ms = [](double s) { return static_cast<long>(std::ceil(s * 1000)); };
        curl_easy_setopt(h, CURLOPT_URL, url.c_str());
        curl_easy_setopt(h, CURLOPT_PROTOCOLS_STR, "http,https");
        curl_easy_setopt(h, CURLOPT_NOSIGNAL, 1L);
        curl_easy_setopt(h, CURLOPT_ERRORBUFFER, error_buffer);
        curl_easy_setopt(h, CURLOPT_USERAGENT, "geotex/" GEOTEX_VERSION);
        curl_easy_setopt(h, CURLOPT_HTTPHEADER, headers.get());
        curl_easy_setopt(h, CURLOPT_POSTFIELDS, data.data());
        curl_easy_setopt(h, CURLOPT_POSTFIELDSIZE_LARGE, static_cast<curl_off_t>(data.size()));
        if (method == HttpMethod::Put) curl_easy_setopt(h, CURLOPT_CUSTOMREQUEST, "PUT");
        curl_easy_setopt(h, CURLOPT_TIMEOUT_MS, ms(settings.timeout));
        curl_easy_setopt(h, CURLOPT_CONNECTTIMEOUT_MS, ms(std::min(settings.timeout, 10.0)));
        curl_easy_setopt(h, CURLOPT_WRITEFUNCTION, &Impl::on_body);
        curl_easy_setopt(h, CURLOPT_WRITEDATA, this);
        curl_easy_setopt(h, CURLOPT_HEADERFUNCTION, &Impl::on_header);
        curl_easy_setopt(h, CURLOPT_HEADERDATA, this);
        if (!settings.user.empty()) {
            curl_easy_setopt(h, CURLOPT_USERNAME, settings.user.c_str());
            curl_easy_setopt(h, CURLOPT_PASSWORD, settings.password.c_str());
            const long auth = settings.auth == "basic"    ? CURLAUTH_BASIC
                              : settings.auth == "digest" ? CURLAUTH_DIGEST
                                                          : CURLAUTH_BASIC | CURLAUTH_DIGEST;
            curl_easy_setopt(h, CURLOPT_HTTPAUTH, auth);
        }
        const CURLcode rc = curl_easy_perform(h);
        status = 0;
        curl_easy_getinfo(h, CURLINFO_RESPONSE_CODE, &status);
        // Nothing of this request may outlive it in the reused handle.
        curl_easy_setopt(h, CURLOPT_HTTPHEADER, nullptr);
        return rc;
    }
};

GraphStoreClient::GraphStoreClient(GraphStoreSettings settings,
                                   std::function<void(const std::string&)> on_retry)
    : impl_(std::make_unique<Impl>()) {
    global_init();
    impl_->settings = std::move(settings);
    impl_->on_retry = std::move(on_retry);
    impl_->curl.reset(curl_easy_init());
    if (!impl_->curl) throw CliError(kExitProcessing, "libcurl could not start a session");
}

GraphStoreClient::~GraphStoreClient() = default;

std::string graph_store_url(const std::string& endpoint, const std::string& graph) {
    global_init();
    // Every byte but the unreserved characters is percent-encoded (libcurl ignores the
    // handle argument since 7.82).
    char* escaped = curl_easy_escape(nullptr, graph.data(), static_cast<int>(graph.size()));
    if (!escaped) throw CliError(kExitProcessing, "libcurl: out of memory");
    std::string url =
        endpoint + (endpoint.find('?') == std::string::npos ? "?" : "&") + "graph=" + escaped;
    curl_free(escaped);
    return url;
}

GraphStoreReply GraphStoreClient::send(HttpMethod method, const std::string& graph,
                                       std::string_view body, const std::string& content_type) {
    Impl& d = *impl_;
    const std::string url = graph_store_url(d.settings.endpoint, graph);
    GraphStoreReply reply;
    double delay = d.settings.retry_delay;
    for (int attempt = 0;; ++attempt) {
        reply.attempts = attempt + 1;
        long status = 0;
        const CURLcode rc = d.attempt(method, url, body, content_type, status);
        reply.status = status;
        bool retry = false;
        if (rc != CURLE_OK) {
            reply.error = std::string(curl_easy_strerror(rc));
            if (d.error_buffer[0] != '\0' && reply.error != d.error_buffer)
                reply.error += " (" + std::string(d.error_buffer) + ")";
            reply.endpoint_failed = true;
            retry = retryable(rc);
        } else if (status >= 200 && status < 300) {
            reply.ok = true;
            reply.error.clear();
            reply.endpoint_failed = false;
            return reply;
        } else {
            std::string line =
                d.status_line.empty() ? "HTTP " + std::to_string(status) : d.status_line;
            // "HTTP/1.1 500 Request Failed" -> "HTTP 500 Request Failed"
            const auto space = line.find(' ');
            if (line.rfind("HTTP/", 0) == 0 && space != std::string::npos)
                line = "HTTP" + line.substr(space);
            const std::string text = body_excerpt(redact_credentials(d.body, d.settings));
            reply.error = line + (text.empty() ? "" : ": " + text);
            // 501 and 505: the server does not do PUT/POST (e.g. a path that is no Graph
            // Store endpoint, where Virtuoso answers 501): no retry helps, no request will do.
            reply.endpoint_failed = status == 401 || status == 403 || status == 404 ||
                                    status == 405 || status == 501 || status == 505 ||
                                    (status >= 300 && status < 400);
            retry = status >= 500 && status != 501 && status != 505;
        }
        if (!retry || attempt >= d.settings.retries) return reply;
        if (d.on_retry) {
            char seconds[32];
            std::snprintf(seconds, sizeof seconds, "%g", delay);
            d.on_retry(reply.error + "; retrying in " + seconds + " s (attempt " +
                       std::to_string(attempt + 2) + " of " +
                       std::to_string(d.settings.retries + 1) + ")");
        }
        std::this_thread::sleep_for(std::chrono::duration<double>(delay));
        delay *= 2;
    }
}

}  // namespace geotex::cli
