#include <visp3/morph_vs/vpMorphHandEyeExploration.h>

#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Dense>

#include <visp3/core/vpRotationMatrix.h>
#include <visp3/core/vpVelocityTwistMatrix.h>
#include <visp3/morph/vpMorphException.h>

void vpMorphHandEyeExploration::setAngle(double rad, unsigned int imageWidth, unsigned int imageHeight)
{
  if (!std::isfinite(rad) || rad < 0.0 || rad > M_PI) {
    std::ostringstream os;
    os << "vpMorphHandEyeExploration::setAngle: the turn must be in [0, pi] rad, got " << rad;
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
  if (rad > 0.0 && (imageWidth == 0 || imageHeight == 0))
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphHandEyeExploration::setAngle: the image's size is needed (0 given)");
  m_angle = rad;
  m_width = imageWidth;
  m_height = imageHeight;
  reset();
}

void vpMorphHandEyeExploration::reset()
{
  m_phase = m_angle > 0.0 ? OUT : NONE;
  m_theta = m_lastReadTheta = m_lastTurn = 0.0;
  m_turned = 0.0;
  m_jumps = m_since = m_count = m_pass = 0;
  m_correction = vpThetaUVector(0, 0, 0);
  m_samples.clear();
}

vpMorphHandEyeExploration::Result vpMorphHandEyeExploration::step(
    const vpMorphContour &current, const vpMorphContour &currentN, const vpMorphContour &targetN, double Zd,
    const vpMorphRigidTransform *currentToTarget, const vpCameraParameters &cam, vpMorphTiltEstimator &tilt,
    vpMorphHandEyeEstimator &handEye, const vpMatrix &eJe, const vpColVector &q, const vpColVector &qMin,
    const vpColVector &qMax, double dt, double jumpPx, vpColVector &ve)
{
  m_lastTurn = 0.0;
  if (!isActive())
    return FINISHED;
  double cx, cy;
  current.centroid(cx, cy);
  const double area = current.area();
  double border = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < current.size(); ++k)
    border =
        std::min({border, current.x(k), current.y(k), m_width - 1.0 - current.x(k), m_height - 1.0 - current.y(k)});
  // A turn that the joints cannot make (their limits, with the Jacobian of the start) is not started.
  if (m_count == 0 && m_pass == 0 && q.size() > 0) {
    vpColVector xi(6, 0.0);
    xi[5] = m_angle;
    const vpColVector qEnd = q + eJe.pseudoInverse() * (vpVelocityTwistMatrix(handEye.get_eMc()) * xi);
    for (unsigned int i = 0; i < qEnd.size() && i < qMin.size(); ++i)
      if (!(qEnd[i] >= qMin[i] && qEnd[i] <= qMax[i])) {
        m_phase = DONE;
        return FINISHED;
      }
  }
  const bool comingBack = m_phase == BACK;
  if (border < getBorderPx() && m_phase == OUT && m_theta > 0.0)
    m_phase = BACK;
  if (m_count > 0) {
    // The view turns by the commanded angle about the principal point, drifting by the turn's own tilt.
    const double u0 = cam.get_u0(), v0 = cam.get_v0(), c = std::cos(m_turned), s = std::sin(m_turned);
    const double px = u0 + c * (m_cx - u0) + s * (m_cy - v0);
    const double py = v0 - s * (m_cx - u0) + c * (m_cy - v0);
    const bool areaKept = std::fabs(area / m_area - 1.0) < getAreaChange();
    const bool onTheWay = std::hypot(cx - px, cy - py) <= jumpPx + getDriftPx() * std::max(0.0, m_since - 1.0);
    if (!areaKept || !onTheWay) {
      m_jumps = areaKept ? m_jumps + 1 : 0;
      if (m_jumps >= getJumpPeriods()) {
        m_phase = DONE;
        return DISPLACED;
      }
      return command(handEye, dt, ve) ? TURNING : FINISHED;
    }
  }
  m_jumps = m_since = 0;
  m_cx = cx;
  m_cy = cy;
  m_area = area;
  m_turned = 0.0;
  if (border < getBorderPx() && (m_theta == 0.0 || comingBack)) {
    m_phase = DONE;
    return FINISHED;
  }
  Sample smp;
  if (currentToTarget && tilt.read(currentN, targetN, Zd, m_theta - m_lastReadTheta, *currentToTarget, smp.r)) {
    smp.theta = m_theta;
    m_lastReadTheta = m_theta;
    m_samples.push_back(smp);
  }
  // A view whose tilt cannot be read (bent, partly hidden) is so from its start: back at once.
  const bool unread = m_samples.empty() && m_count >= 1;
  if (m_phase == OUT && (unread || (std::fabs(m_theta) >= getProbeAngle() && 2 * m_samples.size() < m_count))) {
    m_samples.clear();
    m_phase = BACK;
  }
  return command(handEye, dt, ve) ? TURNING : FINISHED;
}

bool vpMorphHandEyeExploration::command(vpMorphHandEyeEstimator &handEye, double dt, vpColVector &ve)
{
  ++m_count;
  const double step = getSpeed() * dt;
  double w = 0.0;
  if (m_phase == OUT) {
    w = std::min(step, m_angle - m_theta);
    if (m_theta + w >= m_angle - 1e-12)
      m_phase = BACK;
  } else if (m_theta > 1e-12) {
    w = -std::min(step, m_theta);
  } else {
    // Back where it started. The correction is the tilt seen through the intrinsics, off by their error: a second
    // turn through the corrected eMc reads what is left.
    const double corrected = finish(handEye);
    if (!(corrected > getRepeatAbove()) || ++m_pass >= getPasses())
      return false;
    m_phase = OUT;
    m_samples.clear();
    m_count = 0;
    m_lastReadTheta = 0.0;
    w = step;
  }
  m_theta += w;
  m_turned += w;
  m_lastTurn = w;
  ++m_since;
  vpColVector vc(6, 0.0);
  vc[5] = w / dt;
  ve = vpVelocityTwistMatrix(handEye.get_eMc()) * vc;
  return true;
}

double vpMorphHandEyeExploration::finish(vpMorphHandEyeEstimator &handEye)
{
  m_phase = DONE;
  if (m_samples.size() < 8)
    return 0.0;
  Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
  Eigen::Vector4d b = Eigen::Vector4d::Zero();
  std::vector<std::pair<Eigen::Matrix<double, 2, 4>, Eigen::Matrix2d>> rows;
  for (const Sample &s : m_samples) {
    Eigen::Matrix2d C;
    C << s.r.c00, s.r.c01, s.r.c01, s.r.c11;
    const Eigen::Matrix2d J = C.inverse();
    const double c = std::cos(s.theta), sn = std::sin(s.theta);
    Eigen::Matrix<double, 2, 4> M;
    M << 1, 0, c, sn, 0, 1, -sn, c;
    A += M.transpose() * J * M;
    b += M.transpose() * J * Eigen::Vector2d(s.r.nx, s.r.ny);
    rows.emplace_back(M, J);
  }
  const Eigen::Vector4d x = Eigen::LDLT<Eigen::Matrix4d>(A).solve(b);
  double chi2 = 0.0;
  for (std::size_t k = 0; k < m_samples.size(); ++k) {
    const Eigen::Vector2d e = rows[k].first * x - Eigen::Vector2d(m_samples[k].r.nx, m_samples[k].r.ny);
    chi2 += e.transpose() * rows[k].second * e;
  }
  const double kappa = std::max(1.0, chi2 / (2.0 * m_samples.size() - 4.0));
  const Eigen::Matrix4d cov = kappa * A.inverse();
  const double sdA = std::sqrt(std::max(cov(0, 0), cov(1, 1)));
  // Applied when it stands out of the readings' scatter and, at the first turn, is a tilt the final approach could not
  // be sure to take back on a thin object: below getMinCorrection(), an estimate off by its deviation would tilt a
  // camera mounted right.
  const double tiltAngle = std::hypot(x[0], x[1]);
  if (!x.allFinite() || !(sdA < getMaxDeviation()) || (m_pass == 0 && tiltAngle < getMinCorrection()) ||
      tiltAngle < getCorrectionSigmas() * sdA)
    return 0.0;
  // The commanded turn's axis, seen in the true camera, is z + a: turning eMc by the rotation that takes z to z - a
  // makes it the optical axis.
  const vpHomogeneousMatrix Q(0, 0, 0, x[1], -x[0], 0);
  handEye.reset(handEye.get_eMc() * Q);
  m_correction = vpThetaUVector(vpRotationMatrix(m_correction) * Q.getRotationMatrix());
  return tiltAngle;
}
