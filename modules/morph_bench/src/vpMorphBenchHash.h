/*!
  \file vpMorphBenchHash.h
  \brief Internal: a stable hash of names (FNV-1a, 64 bits), the same on every machine and compiler.
*/
#ifndef VP_MORPH_BENCH_HASH_H
#define VP_MORPH_BENCH_HASH_H

#include <cstdint>
#include <string>

namespace vpMorphBenchHash
{
//! FNV-1a 64 of \e text.
inline std::uint64_t fnv1a(const std::string &text)
{
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}
//! Its low and high 32-bit words, to seed a std::seed_seq.
inline unsigned int low(const std::string &text) { return static_cast<unsigned int>(fnv1a(text) & 0xffffffffu); }
inline unsigned int high(const std::string &text) { return static_cast<unsigned int>(fnv1a(text) >> 32); }
} // namespace vpMorphBenchHash

#endif
