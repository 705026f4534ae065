#pragma once
/// The request checks of `geotex view` (view/README.md, Security), as pure functions of the
/// request's headers so that each case is testable without a server: the Host check against
/// DNS rebinding, the Origin check against cross-origin pages, the per-run token, and the
/// object ids that may name a directory under PATH.

#include <optional>
#include <string>

namespace geotex::view {

/// Where the server listens and what a request must carry.
struct AccessPolicy {
    std::string listen_host = "127.0.0.1";  ///< --host ADDR, or the default loopback address
    bool custom_host = false;               ///< --host given: every request needs the token
    int port = 0;                           ///< the port actually bound (never 0 once serving)
    std::string token;                      ///< the run's token (hex)
};

/// What a request brings that the checks look at. Absent headers are nullopt, so that an
/// empty header (`Origin:`) is told apart from a missing one.
struct RequestFacts {
    std::string method;                       ///< "GET", "POST", ...
    std::optional<std::string> host;          ///< Host header
    std::optional<std::string> origin;        ///< Origin header
    std::optional<std::string> header_token;  ///< X-Geotex-Token header
    std::optional<std::string> query_token;   ///< ?token= parameter
    std::optional<std::string> cookie_token;  ///< geotex_token cookie (set with --host)
};

/// True when `host` (a Host header) names the server: "127.0.0.1:N", "localhost:N" or
/// "[::1]:N" with N the policy's port, or "ADDR:N" with --host ("[ADDR]:N" for an IPv6
/// ADDR). Host names compare without case; the port must be written, and be N exactly.
bool host_allowed(const std::string& host, const AccessPolicy& policy);

/// True when `origin` (an Origin header) is "http://" followed by an allowed host (same host
/// and port as the server). "null", https, another port or path are refused.
bool origin_allowed(const std::string& origin, const AccessPolicy& policy);

/// Compares a presented token with the run's in time independent of where they differ. False
/// for an empty run token (never "both empty, equal").
bool token_matches(const std::string& presented, const std::string& token);

/// The verdict on one request: empty when it may go on, else the one-line reason for a 403.
/// Host and Origin always; the token on every POST (header only: a form cannot set it), and
/// with --host on every request (header, ?token= or the cookie the first page load got).
std::string check_request(const RequestFacts& request, const AccessPolicy& policy);

/// A new random 128-bit token as 32 lower-case hexadecimal digits, from the system's random
/// source (std::random_device, /dev/urandom on Linux). Throws IoError when it fails.
std::string make_token();

/// Empty when `id` may name an object directory under PATH: 1..255 bytes, no '/', no '\\',
/// no NUL or other control character, not starting with '.' (so neither "." nor ".." nor a
/// hidden file). Else why not, in a few words.
std::string object_id_problem(const std::string& id);

/// The value of cookie `name` in a Cookie header ("a=1; b=2"), or nullopt.
std::optional<std::string> cookie_value(const std::string& cookie_header, const std::string& name);

}  // namespace geotex::view
