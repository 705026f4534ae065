#include "view/security.hpp"

#include <array>
#include <cctype>
#include <random>

#include "common/errors.hpp"

namespace geotex::view {

namespace {

std::string lower(std::string text) {
    for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

// The host names a request may use for this server, as they appear in a Host header (an
// IPv6 address in brackets), lower case.
std::vector<std::string> allowed_names(const AccessPolicy& policy) {
    std::vector<std::string> names = {"127.0.0.1", "localhost", "[::1]"};
    if (policy.custom_host) {
        const std::string addr = lower(policy.listen_host);
        names.push_back(
            addr.find(':') != std::string::npos && addr.front() != '[' ? "[" + addr + "]" : addr);
    }
    return names;
}

}  // namespace

bool host_allowed(const std::string& host, const AccessPolicy& policy) {
    if (policy.port <= 0) return false;
    // The port is what follows the last colon, which for a bracketed IPv6 address comes after
    // the closing bracket; a missing port is refused, since the server never runs on 80 by
    // default and a browser writes every other port.
    const std::size_t colon = host.rfind(':');
    if (colon == std::string::npos || colon + 1 == host.size()) return false;
    const std::string name = lower(host.substr(0, colon));
    const std::string port = host.substr(colon + 1);
    if (name.empty() || (name.front() == '[') != (name.back() == ']')) return false;
    if (name.front() != '[' && name.find(':') != std::string::npos) return false;
    if (port.size() > 5) return false;
    for (char c : port)
        if (!std::isdigit(static_cast<unsigned char>(c))) return false;
    if (port.size() > 1 && port.front() == '0') return false;
    if (std::stoi(port) != policy.port) return false;
    for (const std::string& allowed : allowed_names(policy))
        if (name == allowed) return true;
    return false;
}

bool origin_allowed(const std::string& origin, const AccessPolicy& policy) {
    static const std::string kScheme = "http://";
    if (origin.size() <= kScheme.size() || lower(origin.substr(0, kScheme.size())) != kScheme)
        return false;
    const std::string rest = origin.substr(kScheme.size());
    // An Origin is scheme://host[:port] and nothing more: a path, user or query is no origin.
    if (rest.find_first_of("/?#@") != std::string::npos) return false;
    return host_allowed(rest, policy);
}

bool token_matches(const std::string& presented, const std::string& token) {
    if (token.empty() || presented.size() != token.size()) return false;
    unsigned char diff = 0;
    for (std::size_t i = 0; i < token.size(); ++i)
        diff |= static_cast<unsigned char>(presented[i] ^ token[i]);
    return diff == 0;
}

std::string check_request(const RequestFacts& request, const AccessPolicy& policy) {
    if (!request.host) return "no Host header";
    if (!host_allowed(*request.host, policy))
        return "Host '" + *request.host + "' is not this server (DNS rebinding?)";
    if (request.origin && !origin_allowed(*request.origin, policy))
        return "Origin '" + *request.origin + "' is not this server";
    const bool header_ok =
        request.header_token && token_matches(*request.header_token, policy.token);
    if (request.method != "GET" && request.method != "HEAD") {
        if (!header_ok)
            return "a " + request.method + " needs the header X-Geotex-Token of this run";
        return {};
    }
    if (policy.custom_host && !header_ok &&
        !(request.query_token && token_matches(*request.query_token, policy.token)) &&
        !(request.cookie_token && token_matches(*request.cookie_token, policy.token)))
        return "with --host every request needs the token printed at start (?token=...)";
    return {};
}

std::string make_token() {
    try {
        std::random_device device("/dev/urandom");
        static const char kHex[] = "0123456789abcdef";
        std::string token;
        for (int word = 0; word < 4; ++word) {
            const std::uint32_t bits = device();
            for (int nibble = 7; nibble >= 0; --nibble) token += kHex[(bits >> (4 * nibble)) & 15];
        }
        return token;
    } catch (const std::exception& e) {
        throw IoError(std::string("cannot draw a random token: ") + e.what(), "/dev/urandom");
    }
}

std::string object_id_problem(const std::string& id) {
    if (id.empty()) return "empty";
    if (id.size() > 255) return "longer than 255 bytes";
    if (id.front() == '.') return "starts with '.'";
    for (char c : id) {
        if (c == '/' || c == '\\') return "holds a slash";
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return "holds a control character";
    }
    return {};
}

std::optional<std::string> cookie_value(const std::string& cookie_header, const std::string& name) {
    std::size_t begin = 0;
    while (begin < cookie_header.size()) {
        std::size_t end = cookie_header.find(';', begin);
        if (end == std::string::npos) end = cookie_header.size();
        std::size_t first = begin;
        while (first < end && cookie_header[first] == ' ') ++first;
        const std::size_t eq = cookie_header.find('=', first);
        if (eq != std::string::npos && eq < end &&
            cookie_header.compare(first, eq - first, name) == 0 && eq - first == name.size())
            return cookie_header.substr(eq + 1, end - eq - 1);
        begin = end + 1;
    }
    return std::nullopt;
}

}  // namespace geotex::view
