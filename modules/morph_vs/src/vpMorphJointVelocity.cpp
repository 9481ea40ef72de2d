#include <visp3/morph_vs/vpMorphJointVelocity.h>

#include "vpMorphParameterCheck.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <visp3/morph/vpMorphException.h>

namespace
{
// Singular values below this (relative) are dropped, as vpMorphSimRobot's own conversion does.
constexpr double kSvThreshold = 1e-6;

bool finite(const vpArray2D<double> &a)
{
  for (unsigned int i = 0; i < a.size(); ++i)
    if (!std::isfinite(a.data[i]))
      return false;
  return true;
}
} // namespace

vpMorphJointVelocity::vpMorphJointVelocity(double samplingTime) : m_dt(0.0) { setSamplingTime(samplingTime); }

void vpMorphJointVelocity::setSamplingTime(double samplingTime)
{
  vpMorphParameterCheck::positive(samplingTime, "vpMorphJointVelocity", "the sampling time");
  m_dt = samplingTime;
}

void vpMorphJointVelocity::reset()
{
  // Moved from empty ones: ViSP's resize() to 0 passes a null pointer to memset (UBSan).
  m_prevJ = vpMatrix();
  m_prevQ = vpColVector();
}

vpColVector vpMorphJointVelocity::compute(const vpMatrix &eJe, const vpColVector &q, const vpColVector &ve)
{
  if (eJe.getRows() != 6 || eJe.getCols() == 0 || q.size() != eJe.getCols() || ve.size() != 6) {
    std::ostringstream os;
    os << "vpMorphJointVelocity::compute: eJe must be 6 x n with n joint positions and a 6-vector twist (got eJe "
       << eJe.getRows() << " x " << eJe.getCols() << ", " << q.size() << " joints, a " << ve.size() << "-vector)";
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
  if (!finite(eJe) || !finite(q) || !finite(ve))
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphJointVelocity::compute: NaN or infinite value in eJe, q or the twist");
  vpColVector qdot = eJe.pseudoInverse(kSvThreshold) * ve;
  if (m_prevQ.size() == q.size() && m_prevJ.getCols() == eJe.getCols()) {
    const vpColVector dq = q - m_prevQ;
    const double dq2 = dq.sumSquare();
    if (dq2 > 0.0) {
      const double a = std::clamp(m_dt * vpColVector::dotProd(qdot, dq) / dq2, -kMaxStepRatio, kMaxStepRatio);
      const vpMatrix Jmid = eJe + (0.5 * a) * (eJe - m_prevJ);
      qdot = Jmid.pseudoInverse(kSvThreshold) * ve;
    }
  }
  m_prevJ = eJe;
  m_prevQ = q;
  return qdot;
}
