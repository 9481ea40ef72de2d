#include <visp3/morph/vpMorphRigidShape.h>

#include <cmath>

#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphOutlineBlur.h>

#include "vpMorphRigidShapeData.h"

// vpMorphRigidShape's blur ladder.

const vpMorphRigidShape &vpMorphRigidShape::atBlur(double blur) const
{
  if (empty())
    throw vpMorphException(vpMorphException::badParameterError, "vpMorphRigidShape::atBlur: empty shape");
  const vpMorphRigidShapeData &d = *m_data;
  const double own = d.contour.outlineBlur();
  if (!d.measured || d.contour.units() != vpMorphContour::PIXEL || !std::isfinite(blur) || !(blur > own))
    return *this;
  // The nearest of this shape's blur and the two rungs about \e blur that a laying can reach (it integrates the
  // pixels once more: vpMorphOutlineBlur::leastBlur()).
  const double least = vpMorphOutlineBlur::leastBlur(d.contour);
  int rung = -1;
  double off = blur - own;
  const int below = static_cast<int>(std::floor(blur / blurRung()));
  for (int k = below; k <= below + 1; ++k) {
    const double b = k * blurRung();
    if (b > least && std::fabs(blur - b) < off) {
      rung = k;
      off = std::fabs(blur - b);
    }
  }
  if (rung < 0)
    return *this;
  std::lock_guard<std::mutex> lock(d.ladderMutex);
  auto it = d.ladder.find(rung);
  if (it == d.ladder.end()) {
    vpMorphRigidShape laid;
    try {
      laid = vpMorphRigidShape(vpMorphOutlineBlur::blurredTo(d.contour, rung * blurRung()));
    } catch (const vpMorphException &) {
      // the blur erases the part (thinner than it everywhere): compared as it is
    }
    it = d.ladder.emplace(rung, laid).first;
  }
  return it->second.empty() ? *this : it->second;
}
