#include "annotation/digest.hpp"

#include <openssl/evp.h>

#include "common/errors.hpp"

namespace geotex {

namespace {

std::string to_hex(const unsigned char* digest, unsigned int size) {
    static constexpr char kHex[] = "0123456789abcdef";
    std::string hex(2 * size, '0');
    for (unsigned int i = 0; i < size; ++i) {
        hex[2 * i] = kHex[digest[i] >> 4];
        hex[2 * i + 1] = kHex[digest[i] & 0x0F];
    }
    return hex;
}

int hex_value(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

}  // namespace

std::string ni_name(std::string_view hex) {
    if (hex.size() != 64)
        throw InvalidInput("ni_name: a SHA-256 digest has 64 hexadecimal digits, not " +
                           std::to_string(hex.size()));
    unsigned char bytes[32];
    for (std::size_t i = 0; i < 32; ++i) {
        const int hi = hex_value(hex[2 * i]), lo = hex_value(hex[2 * i + 1]);
        if (hi < 0 || lo < 0)
            throw InvalidInput("ni_name: '" + std::string(hex.substr(2 * i, 2)) + "' at position " +
                               std::to_string(2 * i + 1) + " of the digest is not hexadecimal");
        bytes[i] = static_cast<unsigned char>(hi * 16 + lo);
    }
    // OpenSSL's base64 (44 characters with one '=' for 32 bytes), then RFC 4648's URL-safe
    // alphabet without padding, as RFC 6920 section 3 asks.
    unsigned char b64[64];
    const int n = EVP_EncodeBlock(b64, bytes, 32);
    std::string out = "ni:///sha-256;";
    for (int i = 0; i < n; ++i) {
        const char c = static_cast<char>(b64[i]);
        if (c == '=') break;
        out += c == '+' ? '-' : c == '/' ? '_' : c;
    }
    return out;
}

std::string sha256_hex(std::string_view bytes) {
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int size = 0;
    if (EVP_Digest(bytes.data(), bytes.size(), digest, &size, EVP_sha256(), nullptr) != 1 ||
        size != 32)
        throw Error("sha256_hex: OpenSSL's EVP SHA-256 digest failed (" +
                    std::to_string(bytes.size()) + " bytes)");
    return to_hex(digest, size);
}

Sha256::Sha256() : context_(EVP_MD_CTX_new()) {
    if (context_ == nullptr ||
        EVP_DigestInit_ex(static_cast<EVP_MD_CTX*>(context_), EVP_sha256(), nullptr) != 1) {
        EVP_MD_CTX_free(static_cast<EVP_MD_CTX*>(context_));
        throw Error("Sha256: OpenSSL's EVP SHA-256 could not start");
    }
}

Sha256::~Sha256() { EVP_MD_CTX_free(static_cast<EVP_MD_CTX*>(context_)); }

void Sha256::update(std::string_view bytes) {
    if (EVP_DigestUpdate(static_cast<EVP_MD_CTX*>(context_), bytes.data(), bytes.size()) != 1)
        throw Error("Sha256: OpenSSL's EVP SHA-256 update failed");
}

std::string Sha256::hex() {
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int size = 0;
    if (EVP_DigestFinal_ex(static_cast<EVP_MD_CTX*>(context_), digest, &size) != 1 || size != 32)
        throw Error("Sha256: OpenSSL's EVP SHA-256 digest failed");
    return to_hex(digest, size);
}

}  // namespace geotex
