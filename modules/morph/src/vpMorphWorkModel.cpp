#include <visp3/morph/vpMorphWorkModel.h>

#include <cmath>
#include <sstream>

#include <visp3/morph/vpMorphException.h>

vpMorphWorkModel::vpMorphWorkModel(double ks, double kb, double cs) : m_ks(ks), m_kb(kb), m_cs(cs)
{
  std::ostringstream err;
  if (!std::isfinite(ks) || ks <= 0.0)
    err << "stretching stiffness ks must be finite and > 0 (got " << ks << ")";
  else if (!std::isfinite(kb) || kb <= 0.0)
    err << "bending stiffness kb must be finite and > 0 (got " << kb << ")";
  else if (!std::isfinite(cs) || cs <= 0.0 || cs > 1.0)
    err << "collapse penalty cs must be in (0, 1] (got " << cs << ")";
  if (!err.str().empty())
    throw vpMorphException(vpMorphException::badParameterError, "vpMorphWorkModel: " + err.str());
}
