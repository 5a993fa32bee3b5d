#pragma once
// FNV-1a, 64 bit (Fowler, Noll and Vo): a fast non-cryptographic hash for recognising data again
// (a scene's fingerprint, a checkpoint's checksum), not for security. `hash` chains several parts.
#include <cstdint>
#include <string_view>

namespace moreau {

inline constexpr std::uint64_t kFnv1aOffset = 14695981039346656037ull;

inline std::uint64_t fnv1a(std::string_view bytes, std::uint64_t hash = kFnv1aOffset) {
  for (unsigned char c : bytes) hash = (hash ^ c) * 1099511628211ull;
  return hash;
}

}  // namespace moreau
