#include <visp3/morph_vs/vpMorphJointVelocity.h>

#include "vpMorphParameterCheck.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <visp3/core/vpExponentialMap.h>
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

void vpMorphJointVelocity::setKinematicModel(const KinematicModel &model)
{
  if (static_cast<bool>(model.fMe) != static_cast<bool>(model.eJe))
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphJointVelocity::setKinematicModel: set both fMe(q) and eJe(q), or neither");
  m_model = model;
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
  if (m_model.isSet())
    qdot = solveOnModel(q, ve, qdot);
  else if (m_prevQ.size() == q.size() && m_prevJ.getCols() == eJe.getCols()) {
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

vpColVector vpMorphJointVelocity::solveOnModel(const vpColVector &q, const vpColVector &ve,
                                               const vpColVector &qdot0) const
{
  const vpHomogeneousMatrix fMe_goal = m_model.fMe(q) * vpExponentialMap::direct(ve, m_dt);
  vpColVector dq = qdot0 * m_dt, best = dq;
  double bestResidual = std::numeric_limits<double>::infinity();
  for (unsigned int it = 0; it <= kMaxNewtonIterations; ++it) {
    const vpColVector qk = q + dq;
    // The end-effector twist, over unit time and in its frame at q + dq, that would still reach the goal.
    const vpColVector e = vpExponentialMap::inverse(m_model.fMe(qk).inverse() * fMe_goal, 1.0);
    const double errT = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    const double errR = std::sqrt(e[3] * e[3] + e[4] * e[4] + e[5] * e[5]);
    if (!std::isfinite(errT) || !std::isfinite(errR))
      break;
    const double residual = std::max(errT, errR);
    if (residual < bestResidual) {
      bestResidual = residual;
      best = dq;
    }
    // Near a singularity the step may not be reachable exactly: the closest iterate is kept.
    if (residual < kPoseTolerance || it == kMaxNewtonIterations)
      break;
    const vpMatrix J = m_model.eJe(qk);
    if (J.getRows() != 6 || J.getCols() != q.size())
      throw vpMorphException(vpMorphException::badParameterError,
                             "vpMorphJointVelocity: the kinematic model's eJe(q) is not 6 x n");
    dq += J.pseudoInverse(kSvThreshold) * e;
  }
  return best / m_dt;
}
