#include <catch2/catch.hpp>
#include <string>

#include "annotation/digest.hpp"

using namespace geotex;

TEST_CASE("sha256_hex: FIPS 180-2 test vectors", "[annotation][digest]") {
    CHECK(sha256_hex("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
    CHECK(sha256_hex("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    CHECK(sha256_hex(std::string(1000000, 'a')) ==
          "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
    CHECK(sha256_hex(std::string("a\0b", 3)) != sha256_hex("a"));  // bytes, not C strings
}

TEST_CASE("Sha256: fed in pieces, the FIPS 180-2 million-'a' vector", "[annotation][digest]") {
    geotex::Sha256 h;
    const std::string chunk(4096, 'a');
    std::size_t left = 1000000;
    while (left > 0) {  // 244 full chunks and a partial one
        const std::size_t n = std::min(left, chunk.size());
        h.update(std::string_view(chunk).substr(0, n));
        left -= n;
    }
    CHECK(h.hex() == "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
    geotex::Sha256 empty;
    CHECK(empty.hex() == sha256_hex(""));
}
