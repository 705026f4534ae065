// The request checks of geotex view (view/README.md, Security), case by case.

#include <catch2/catch.hpp>
#include <set>

#include "view/security.hpp"

using namespace geotex::view;

namespace {

AccessPolicy loopback() {
    AccessPolicy p;
    p.port = 8765;
    p.token = "0123456789abcdef0123456789abcdef";
    return p;
}

RequestFacts get(const std::string& host) {
    RequestFacts r;
    r.method = "GET";
    r.host = host;
    return r;
}

}  // namespace

TEST_CASE("host_allowed: the loopback names with the server's port only", "[view][security]") {
    const AccessPolicy p = loopback();
    CHECK(host_allowed("127.0.0.1:8765", p));
    CHECK(host_allowed("localhost:8765", p));
    CHECK(host_allowed("LocalHost:8765", p));
    CHECK(host_allowed("[::1]:8765", p));
    // DNS rebinding: a name the attacker controls resolves to 127.0.0.1, and the browser
    // sends that name.
    CHECK_FALSE(host_allowed("evil.example:8765", p));
    CHECK_FALSE(host_allowed("127.0.0.1.evil.example:8765", p));
    // Another port (another local service's page), no port, a malformed port.
    CHECK_FALSE(host_allowed("127.0.0.1:8766", p));
    CHECK_FALSE(host_allowed("127.0.0.1", p));
    CHECK_FALSE(host_allowed("127.0.0.1:", p));
    CHECK_FALSE(host_allowed("127.0.0.1:08765", p));
    CHECK_FALSE(host_allowed("127.0.0.1:+8765", p));
    CHECK_FALSE(host_allowed("127.0.0.1:87650", p));
    CHECK_FALSE(host_allowed("::1:8765", p));  // IPv6 without brackets
    CHECK_FALSE(host_allowed("[::1:8765", p));
    CHECK_FALSE(host_allowed("", p));
    // A server that has not bound yet allows nothing.
    AccessPolicy unbound = p;
    unbound.port = 0;
    CHECK_FALSE(host_allowed("127.0.0.1:0", unbound));
}

TEST_CASE("host_allowed: --host adds its address", "[view][security]") {
    AccessPolicy p = loopback();
    CHECK_FALSE(host_allowed("192.168.1.5:8765", p));
    p.custom_host = true;
    p.listen_host = "192.168.1.5";
    CHECK(host_allowed("192.168.1.5:8765", p));
    CHECK(host_allowed("127.0.0.1:8765", p));
    CHECK_FALSE(host_allowed("192.168.1.6:8765", p));
    p.listen_host = "fe80::1";
    CHECK(host_allowed("[fe80::1]:8765", p));
    CHECK_FALSE(host_allowed("fe80::1:8765", p));
}

TEST_CASE("origin_allowed: only the server's own origin", "[view][security]") {
    const AccessPolicy p = loopback();
    CHECK(origin_allowed("http://127.0.0.1:8765", p));
    CHECK(origin_allowed("http://localhost:8765", p));
    CHECK(origin_allowed("http://[::1]:8765", p));
    CHECK_FALSE(origin_allowed("null", p));  // sandboxed iframes, file:// pages
    CHECK_FALSE(origin_allowed("", p));
    CHECK_FALSE(origin_allowed("http://evil.example", p));
    CHECK_FALSE(origin_allowed("http://evil.example:8765", p));
    CHECK_FALSE(origin_allowed("http://127.0.0.1:8766", p));
    CHECK_FALSE(origin_allowed("https://127.0.0.1:8765", p));
    CHECK_FALSE(origin_allowed("http://127.0.0.1:8765/", p));
    CHECK_FALSE(origin_allowed("http://user@127.0.0.1:8765", p));
}

TEST_CASE("check_request: GET needs no token on loopback, POST always does", "[view][security]") {
    const AccessPolicy p = loopback();
    CHECK(check_request(get("127.0.0.1:8765"), p).empty());
    CHECK(check_request(get("localhost:8765"), p).empty());
    CHECK_FALSE(check_request(get("evil.example:8765"), p).empty());
    RequestFacts no_host;
    no_host.method = "GET";
    CHECK_FALSE(check_request(no_host, p).empty());

    RequestFacts foreign = get("127.0.0.1:8765");
    foreign.origin = "http://evil.example";
    CHECK_FALSE(check_request(foreign, p).empty());
    foreign.origin = "null";
    CHECK_FALSE(check_request(foreign, p).empty());
    foreign.origin = "http://127.0.0.1:8765";
    CHECK(check_request(foreign, p).empty());

    RequestFacts post = get("127.0.0.1:8765");
    post.method = "POST";
    CHECK_FALSE(check_request(post, p).empty());  // missing token
    post.header_token = "";
    CHECK_FALSE(check_request(post, p).empty());
    post.header_token = "0123456789abcdef0123456789abcdee";  // one digit off
    CHECK_FALSE(check_request(post, p).empty());
    // A token in the query or a cookie is what any page can make a browser send: a POST
    // takes the header alone.
    post.query_token = p.token;
    post.cookie_token = p.token;
    CHECK_FALSE(check_request(post, p).empty());
    post.header_token = p.token;
    CHECK(check_request(post, p).empty());
    // The right token does not make a foreign origin or host acceptable.
    post.origin = "http://evil.example";
    CHECK_FALSE(check_request(post, p).empty());
    post.origin.reset();
    post.host = "evil.example:8765";
    CHECK_FALSE(check_request(post, p).empty());
}

TEST_CASE("check_request: with --host every request needs the token", "[view][security]") {
    AccessPolicy p = loopback();
    p.custom_host = true;
    p.listen_host = "10.0.0.2";
    RequestFacts r = get("10.0.0.2:8765");
    CHECK_FALSE(check_request(r, p).empty());
    r.query_token = "wrong";
    CHECK_FALSE(check_request(r, p).empty());
    r.query_token = p.token;
    CHECK(check_request(r, p).empty());
    r.query_token.reset();
    r.cookie_token = p.token;
    CHECK(check_request(r, p).empty());
    r.cookie_token.reset();
    r.header_token = p.token;
    CHECK(check_request(r, p).empty());
}

TEST_CASE("token_matches: equal non-empty tokens only", "[view][security]") {
    CHECK(token_matches("abc", "abc"));
    CHECK_FALSE(token_matches("abd", "abc"));
    CHECK_FALSE(token_matches("ab", "abc"));
    CHECK_FALSE(token_matches("abcd", "abc"));
    CHECK_FALSE(token_matches("", ""));
}

TEST_CASE("make_token: 32 hex digits, a new one each time", "[view][security]") {
    std::set<std::string> seen;
    for (int i = 0; i < 50; ++i) {
        const std::string t = make_token();
        REQUIRE(t.size() == 32);
        for (char c : t) CHECK(std::string("0123456789abcdef").find(c) != std::string::npos);
        seen.insert(t);
    }
    CHECK(seen.size() == 50);
}

TEST_CASE("object_id_problem: ids that cannot leave objects/", "[view][security]") {
    CHECK(object_id_problem("obj-1").empty());
    CHECK(object_id_problem("vase 12 (front)").empty());
    CHECK(object_id_problem("a..b").empty());
    CHECK_FALSE(object_id_problem("").empty());
    CHECK_FALSE(object_id_problem(".").empty());
    CHECK_FALSE(object_id_problem("..").empty());
    CHECK_FALSE(object_id_problem(".hidden").empty());
    CHECK_FALSE(object_id_problem("../etc").empty());
    CHECK_FALSE(object_id_problem("a/b").empty());
    CHECK_FALSE(object_id_problem("a\\b").empty());
    CHECK_FALSE(object_id_problem(std::string("a\0b", 3)).empty());
    CHECK_FALSE(object_id_problem("a\nb").empty());
    CHECK_FALSE(object_id_problem(std::string(256, 'a')).empty());
    CHECK(object_id_problem(std::string(255, 'a')).empty());
}

TEST_CASE("cookie_value: one cookie among several", "[view][security]") {
    CHECK(cookie_value("geotex_token=abc", "geotex_token") == std::optional<std::string>("abc"));
    CHECK(cookie_value("a=1; geotex_token=abc; b=2", "geotex_token") ==
          std::optional<std::string>("abc"));
    CHECK_FALSE(cookie_value("xgeotex_token=abc", "geotex_token"));
    CHECK_FALSE(cookie_value("", "geotex_token"));
}
