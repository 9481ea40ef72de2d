#include <visp3/morph_vs/vpMorphHandEyeEstimator.h>

#include "vpMorphParameterCheck.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <visp3/morph/vpMorphException.h>

vpMorphHandEyeEstimator::vpMorphHandEyeEstimator(const vpHomogeneousMatrix &eMc0) { reset(eMc0); }

void vpMorphHandEyeEstimator::reset(const vpHomogeneousMatrix &eMc0)
{
  m_eMc0 = eMc0;
  m_eMc = eMc0;
  // The prior is the first 'observation' (Y = I, k = 1): it is forgotten along with the data, so it only
  // decides what the moves leave unobserved.
  m_M.eye(4);
  m_M *= m_prior;
  m_r.resize(4, true);
  m_r[2] = m_prior;
  m_u = m_r / m_prior; // (0, 0, 1, 0): Y = I, k = 1
  m_moves = 0;
  m_rejected = 0;
  m_eRef = 0.0;
}

void vpMorphHandEyeEstimator::setForgetting(double f)
{
  if (!std::isfinite(f) || f <= 0.0 || f > 1.0) {
    std::ostringstream os;
    os << "vpMorphHandEyeEstimator::setForgetting: the factor must be in (0, 1], got " << f;
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
  m_forget = f;
}

void vpMorphHandEyeEstimator::setPriorWeight(double w)
{
  vpMorphParameterCheck::positive(w, "vpMorphHandEyeEstimator::setPriorWeight", "the weight");
  m_prior = w;
  if (m_moves == 0)
    reset(m_eMc0);
}

void vpMorphHandEyeEstimator::addMove(const vpHomogeneousMatrix &eMe, const vpHomogeneousMatrix &cMc)
{
  const vpHomogeneousMatrix A = m_eMc0.inverse() * eMe * m_eMc0;
  const double phi = std::atan2(A[1][0], A[0][0]);
  const double tax = A[0][3], tay = A[1][3], tbx = cMc[0][3], tby = cMc[1][3];
  if (!std::isfinite(phi) || !std::isfinite(tax) || !std::isfinite(tay) || !std::isfinite(tbx) || !std::isfinite(tby))
    return; // a failed observation adds nothing
  const double c = std::cos(phi), s = std::sin(phi);
  vpMatrix J(2, 4);
  J[0][0] = c - 1;
  J[0][1] = -s;
  J[0][2] = -tbx;
  J[0][3] = tby;
  J[1][0] = s;
  J[1][1] = c - 1;
  J[1][2] = -tby;
  J[1][3] = -tbx;
  vpColVector b(2);
  b[0] = -tax;
  b[1] = -tay;
  // One wrong view (a contour re-digitized across an occluder) must not pull the scale toward 0 and stall the servo:
  // what the current estimate fails to explain is at most the move's own size (twice: any error about the axis, a
  // projection off by up to 3x) plus what the rotation does to an offset error of up to kOutlierOffset.
  const double slack = kOutlierMoves * b.frobeniusNorm() + std::fabs(phi) * kOutlierOffset;
  if ((J * m_u - b).frobeniusNorm() > slack) {
    ++m_rejected;
    return;
  }
  // Information-weighted forgetting: a move forgets the past in proportion to its information (squared norm of
  // its equations) relative to a tenth of the largest so far, so that the tiny moves of the final convergence do
  // not wash out the large moves that determined the estimate.
  const double e = J.frobeniusNorm() * J.frobeniusNorm();
  m_eRef = std::max(m_eRef, 0.1 * e);
  const double f = std::pow(m_forget, m_eRef > 0 ? std::min(1.0, e / m_eRef) : 0.0);
  m_M = m_M * f + J.t() * J;
  m_r = m_r * f + J.t() * b;
  ++m_moves;
  solve();
}

void vpMorphHandEyeEstimator::solve()
{
  vpColVector u = m_M.inverseByLU() * m_r;
  const double k = std::hypot(u[2], u[3]);
  if (!std::isfinite(k) || k < 1e-3 || !std::isfinite(u[0]) || !std::isfinite(u[1]))
    return;
  // The intrinsics given are a calibrated camera's: a scale beyond kMaxTranslationScale is the planar model failing
  // (a tilted view), not a calibration, and would shrink every translation command (\ref page_design_servo).
  const double kb = std::min(kMaxTranslationScale, std::max(1.0 / kMaxTranslationScale, k));
  u[2] *= kb / k;
  u[3] *= kb / k;
  const double psi = std::atan2(u[3], u[2]);
  m_u = u;
  m_eMc = m_eMc0 * vpHomogeneousMatrix(u[0], u[1], 0, 0, 0, psi);
}
