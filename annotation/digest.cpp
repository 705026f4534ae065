#include "annotation/digest.hpp"

#include <openssl/evp.h>

#include "geometry/errors.hpp"

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

}  // namespace

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
    if (context_ == nullptr || EVP_DigestInit_ex(static_cast<EVP_MD_CTX*>(context_), EVP_sha256(), nullptr) != 1) {
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
