#pragma once
/// SHA-256 digests (OpenSSL's libcrypto): of mesh files, for the default base IRI and
/// gtx:sha256, and of dictionary files.

#include <string>
#include <string_view>

namespace geotex {

/// Lower-case hexadecimal SHA-256 of `bytes` (64 characters).
std::string sha256_hex(std::string_view bytes);

}  // namespace geotex
