/*!
  \file vpFuzzInput.h
  \brief Reads typed values from a fuzzer's byte string, and the check that makes a violated invariant a finding.

  Shared by the fuzz targets of tests/fuzz/. Why a reader of our own rather than libFuzzer's FuzzedDataProvider:
  the same target sources are also compiled by gcc into the replay driver (ctest), which has no clang headers.
  Reading past the end yields zeros, so every byte string is a valid input and short seeds stay meaningful.
*/
#ifndef VP_FUZZ_INPUT_H
#define VP_FUZZ_INPUT_H

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

//! Aborts (the fuzzer records the input) when an invariant documented by the project does not hold.
#define VP_FUZZ_CHECK(cond, what)                                                                                   \
  do {                                                                                                              \
    if (!(cond)) {                                                                                                  \
      std::fprintf(stderr, "fuzz invariant violated at %s:%d: %s (%s)\n", __FILE__, __LINE__, what, #cond);         \
      std::abort();                                                                                                 \
    }                                                                                                               \
  } while (0)

/*!
  \class vpFuzzInput
  \brief A cursor over the fuzzer's bytes: bytes, small integers, and doubles that reach the hard values
  (NaN, infinities, huge, tiny, subnormal, negative zero) as easily as ordinary small coordinates.
*/
class vpFuzzInput
{
public:
  vpFuzzInput(const uint8_t *data, std::size_t size) : m_data(data), m_size(size) {}

  std::size_t remaining() const { return m_pos < m_size ? m_size - m_pos : 0; }

  uint8_t byte() { return m_pos < m_size ? m_data[m_pos++] : 0; }

  uint16_t u16()
  {
    const uint16_t lo = byte();
    return static_cast<uint16_t>(lo | (static_cast<uint16_t>(byte()) << 8));
  }

  //! An integer in [lo, hi] from one or two bytes.
  std::size_t range(std::size_t lo, std::size_t hi)
  {
    const std::size_t span = hi - lo + 1;
    const std::size_t v = span <= 256 ? byte() : u16();
    return lo + v % span;
  }

  //! The 8 next bytes as an IEEE double, bit for bit (any NaN payload, subnormals, infinities).
  double rawDouble()
  {
    uint64_t bits = 0;
    for (int k = 0; k < 8; ++k)
      bits |= static_cast<uint64_t>(byte()) << (8 * k);
    double d;
    std::memcpy(&d, &bits, sizeof d);
    return d;
  }

  /*!
    A coordinate: one tag byte chooses a raw double (tag % 16 == 0), one of the hard values (tag % 16 == 1),
    or a small signed integer times \e scale (otherwise: the common case, which makes duplicates, collinear
    runs and integer pixel grids likely).
  */
  double coordinate(double scale = 1.0)
  {
    const uint8_t tag = byte();
    switch (tag % 16) {
    case 0:
      return rawDouble();
    case 1: {
      static const double hard[] = {std::numeric_limits<double>::quiet_NaN(),
                                    std::numeric_limits<double>::infinity(),
                                    -std::numeric_limits<double>::infinity(),
                                    0.0,
                                    -0.0,
                                    1e308,
                                    -1e308,
                                    1e154,
                                    1e-154,
                                    1e-308,
                                    std::numeric_limits<double>::denorm_min(),
                                    std::numeric_limits<double>::max(),
                                    std::numeric_limits<double>::lowest(),
                                    std::numeric_limits<double>::epsilon(),
                                    1e15,
                                    0.5};
      return hard[byte() % 16];
    }
    default:
      return static_cast<int8_t>(byte()) * scale;
    }
  }

  //! A factor for coordinates: 1 mostly, sometimes tiny or huge.
  double scale()
  {
    static const double scales[] = {1.0, 1.0, 1.0, 1.0, 10.0, 0.1, 1e-3, 1e-9, 1e6, 1e12, 1e-300, 1e300};
    return scales[byte() % 12];
  }

  //! The rest of the bytes as text.
  std::string rest()
  {
    const std::size_t n = remaining();
    std::string s(reinterpret_cast<const char *>(m_data + m_pos), n);
    m_pos = m_size;
    return s;
  }

private:
  const uint8_t *m_data;
  std::size_t m_size;
  std::size_t m_pos = 0;
};

#endif
