// The parameter checks of morph_vs's setters (internal): a vpMorphException::badParameterError that names the setter,
// the parameter and the value given.
#ifndef VP_MORPH_PARAMETER_CHECK_H
#define VP_MORPH_PARAMETER_CHECK_H

#include <cmath>
#include <sstream>

#include <visp3/morph/vpMorphException.h>

namespace vpMorphParameterCheck
{
inline void fail(const char *where, const char *what, const char *bound, double v)
{
  std::ostringstream os;
  os << where << ": " << what << " must be finite and " << bound << ", got " << v;
  throw vpMorphException(vpMorphException::badParameterError, os.str());
}
//! Throws unless \e v is finite and > 0.
inline void positive(double v, const char *where, const char *what)
{
  if (!std::isfinite(v) || v <= 0.0)
    fail(where, what, "> 0", v);
}
//! Throws unless \e v is finite and >= 0.
inline void nonNegative(double v, const char *where, const char *what)
{
  if (!std::isfinite(v) || v < 0.0)
    fail(where, what, ">= 0", v);
}
} // namespace vpMorphParameterCheck

#endif
