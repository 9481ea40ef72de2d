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
  // The nearest of this shape's blur and the two rungs about \e blur that a blur can reach (laying an outline
  // integrates the pixels once more: its blur is at least sqrt(own^2 + pixelVariance())).
  const double minimum2 = own * own + vpMorphOutlineBlur::pixelVariance();
  int rung = -1;
  double off = blur - own;
  const int below = static_cast<int>(std::floor(blur / blurRung()));
  for (int k = below; k <= below + 1; ++k) {
    const double b = k * blurRung();
    if (b * b > minimum2 && std::fabs(blur - b) < off) {
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
      const double b = rung * blurRung();
      laid = vpMorphRigidShape(vpMorphOutlineBlur::blurred(d.contour, std::sqrt(b * b - minimum2)));
    } catch (const vpMorphException &) {
      // the blur erases the part (thinner than it everywhere): compared as it is
    }
    it = d.ladder.emplace(rung, laid).first;
  }
  return it->second.empty() ? *this : it->second;
}
