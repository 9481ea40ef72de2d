#include <visp3/morph/vpMorphTemplate.h>

#include <cmath>

#include <visp3/core/vpRotationMatrix.h>
#include <visp3/core/vpRzyxVector.h>
#include <visp3/core/vpTranslationVector.h>
#include <visp3/morph/vpMorphException.h>

vpMorphTemplate::vpMorphTemplate(const std::string &name, const vpMorphContour &contour, const std::string &imagePath,
                                 const vpHomogeneousMatrix &cdMo)
  : m_name(name), m_contour(contour), m_image(imagePath), m_cdMo(cdMo)
{
  if (name.empty())
    throw vpMorphException(vpMorphException::badParameterError, "vpMorphTemplate: a template needs a name");
  if (contour.empty())
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphTemplate: template '" + name + "' has an empty contour");
}

std::string vpMorphTemplate::metadata(const std::string &key, const std::string &fallback) const
{
  auto it = m_meta.find(key);
  return it == m_meta.end() ? fallback : it->second;
}

void vpMorphTemplate::setPlanarPose(double tx, double ty, double Z, double theta)
{
  if (!std::isfinite(tx) || !std::isfinite(ty) || !std::isfinite(Z) || !std::isfinite(theta) || Z <= 0.0)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphTemplate::setPlanarPose: finite values and a positive depth are needed");
  m_cdMo = vpHomogeneousMatrix(vpTranslationVector(tx, ty, Z), vpRotationMatrix(vpRzyxVector(theta, 0.0, 0.0)));
}

void vpMorphTemplate::setArticulation(const vpMorphArticulation &a)
{
  if (!a.empty() && a.part(0).units() != m_contour.units())
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphTemplate::setArticulation: the parts of template '" + m_name +
                               "' are not in its contour's units");
  m_articulation = a;
}

vpMorphContour vpMorphTemplate::viewFor(const vpMorphContour &view, double *opening, unsigned int *fixedPart) const
{
  const double a = isArticulated() ? m_articulation.estimate(view) : 0.0;
  unsigned int k = 0;
  // At the taught opening, the taught view itself, not its parts redrawn.
  vpMorphContour v = a == 0.0 ? m_contour : m_articulation.poseFor(view, a, &k);
  if (opening)
    *opening = a;
  if (fixedPart)
    *fixedPart = k;
  return v;
}
