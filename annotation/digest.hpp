#pragma once
/// SHA-256 digests (OpenSSL's libcrypto): of mesh files, for the default base IRI and
/// gtx:sha256, and of dictionary files.

#include <string>
#include <string_view>

namespace geotex {

/// Lower-case hexadecimal SHA-256 of `bytes` (64 characters).
std::string sha256_hex(std::string_view bytes);

/// The RFC 6920 hash name of a SHA-256 digest given in hexadecimal (64 characters):
/// "ni:///sha-256;" + the digest's 32 bytes in base64url without padding (43 characters).
/// Throws InvalidInput when `hex` is not 64 hexadecimal digits.
std::string ni_name(std::string_view hex);

/// SHA-256 fed in pieces (a file read in chunks, so that a large scan is never held whole).
class Sha256 {
  public:
    Sha256();
    ~Sha256();
    Sha256(const Sha256&) = delete;
    Sha256& operator=(const Sha256&) = delete;

    void update(std::string_view bytes);
    /// Lower-case hexadecimal digest of everything given; ends the computation.
    std::string hex();

  private:
    void* context_;  // EVP_MD_CTX, kept out of this header
};

}  // namespace geotex
