#include "annotation/digest.hpp"

#include <openssl/evp.h>

#include "geometry/errors.hpp"

namespace geotex {

std::string sha256_hex(std::string_view bytes) {
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int size = 0;
    if (EVP_Digest(bytes.data(), bytes.size(), digest, &size, EVP_sha256(), nullptr) != 1 ||
        size != 32)
        throw Error("sha256_hex: OpenSSL's EVP SHA-256 digest failed (" +
                    std::to_string(bytes.size()) + " bytes)");
    static constexpr char kHex[] = "0123456789abcdef";
    std::string hex(2 * size, '0');
    for (unsigned int i = 0; i < size; ++i) {
        hex[2 * i] = kHex[digest[i] >> 4];
        hex[2 * i + 1] = kHex[digest[i] & 0x0F];
    }
    return hex;
}

}  // namespace geotex
