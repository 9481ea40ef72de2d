#include <visp3/morph_vs/vpMorphSubGoalPlanner.h>

#include <cmath>

#include <visp3/core/vpVelocityTwistMatrix.h>
#include <visp3/morph/vpMorph.h>
#include <visp3/morph/vpMorphException.h>

void vpMorphSubGoalPlanner::setJointState(const vpMatrix &eJe, const vpColVector &q, const vpColVector &qMin,
                                          const vpColVector &qMax)
{
  const unsigned int n = q.size();
  if (n == 0 || eJe.getRows() != 6 || eJe.getCols() != n || qMin.size() != n || qMax.size() != n)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphSubGoalPlanner::setJointState: eJe must be 6 x n for n joint positions and limits");
  for (unsigned int i = 0; i < n; ++i)
    if (!(q[i] >= qMin[i] && q[i] <= qMax[i]))
      throw vpMorphException(vpMorphException::badParameterError,
                             "vpMorphSubGoalPlanner::setJointState: a joint position is NaN or outside its limits");
  m_eJe = eJe;
  m_q = q;
  m_qMin = qMin;
  m_qMax = qMax;
}

void vpMorphSubGoalPlanner::clear()
{
  m_goals.clear();
  m_depths.clear();
  m_maps.clear();
  m_rigid = 0;
  m_longWay = false;
  m_qEnd = vpColVector();
}

vpHomogeneousMatrix vpMorphSubGoalPlanner::cameraDisplacement(const vpMorphRigidTransform &T, double Z, double k)
{
  // Image similarity x' = s R(theta) (x - c) + c + t of a plane parallel to the image at depth Z
  // <=> camera move cMc' = [Rz(-theta), (k Z (c - R(-theta)(c + t) / s), Z (1 - 1/s))].
  const double th = T.theta(), s = T.scale(), ct = std::cos(th), st = std::sin(th);
  const double qx = T.cx() + T.tx(), qy = T.cy() + T.ty();
  const double rx = ct * qx + st * qy, ry = -st * qx + ct * qy;
  return vpHomogeneousMatrix(k * Z * (T.cx() - rx / s), k * Z * (T.cy() - ry / s), Z * (1.0 - 1.0 / s), 0, 0, -th);
}

vpColVector vpMorphSubGoalPlanner::jointEnd(const vpMatrix &eJeInv, const vpHomogeneousMatrix &eMc,
                                            const vpHomogeneousMatrix &cMcp, double turn) const
{
  vpColVector xi(6, 0.0); // the plan's camera displacement as a twist: translation d, turn -turn about z
  for (unsigned int i = 0; i < 3; ++i)
    xi[i] = cMcp[i][3];
  xi[5] = -turn;
  return m_q + eJeInv * (vpVelocityTwistMatrix(eMc) * xi);
}

bool vpMorphSubGoalPlanner::nearJointLimit(const vpColVector &q) const
{
  for (unsigned int i = 0; i < q.size(); ++i) {
    const double margin = getJointMargin() * (m_qMax[i] - m_qMin[i]);
    if (std::isfinite(margin) && (q[i] < m_qMin[i] + margin || q[i] > m_qMax[i] - margin))
      return true;
  }
  return false;
}

vpMorphRigidTransform vpMorphSubGoalPlanner::getStep(std::size_t k) const
{
  if (k + 1 >= m_maps.size())
    throw vpMorphException(vpMorphException::badParameterError, "vpMorphSubGoalPlanner::getStep: no sub-goal after k");
  return m_maps[k + 1] * m_maps[k].inverse();
}

void vpMorphSubGoalPlanner::plan(const vpMorphContour &current, const vpMorphContour &target,
                                 const vpMorphRigidTransform &T, const vpCameraParameters &cam, double Zd,
                                 const vpHomogeneousMatrix &eMc, const vpMorphCorrespondence &correspondence)
{
  clear();
  const vpMorphContour currentN = current.toNormalized(cam);
  const double Z = Zd * T.scale(); // the view is s times smaller than the target's at Zd
  const vpHomogeneousMatrix cMcp = cameraDisplacement(T, Z);
  // The short way round unless the joints would end near a limit and the long way keeps them clear.
  const double theta = T.theta(), longTurn = theta - std::copysign(2.0 * M_PI, theta);
  if (m_q.size() > 0) {
    const vpMatrix eJeInv = m_eJe.pseudoInverse();
    m_qEnd = jointEnd(eJeInv, eMc, cMcp, theta);
    const vpColVector qLong = jointEnd(eJeInv, eMc, cMcp, longTurn);
    m_longWay = nearJointLimit(m_qEnd) && !nearJointLimit(qLong);
    if (m_longWay)
      m_qEnd = qLong;
  }
  const double turn = m_longWay ? longTurn : theta;

  std::size_t rigidFrames = m_n > 0 ? m_n - 1 : 0; // the last rigid frame would be the target itself
  std::vector<vpMorphContour> deformation;
  if (m_deformation && m_n > 0) {
    // The paper's sequence: rigid frames by its own count, then the rectified view interpolated to the target.
    const vpMorphContour targetN = target.toNormalized(cam);
    const vpMorph morph(currentN, targetN, correspondence, T);
    rigidFrames = morph.rigidFrameCount(m_n);
    const std::vector<vpMorphContour> seq = morph.sequence(m_n, m_longWay);
    for (std::size_t k = rigidFrames; k + 1 < seq.size(); ++k)
      deformation.push_back(seq[k].toPixels(cam));
  }
  const double nr = double(rigidFrames + 1);
  for (std::size_t k = 1; k <= rigidFrames; ++k) {
    const double a = double(k) / nr;
    vpMorphRigidTransform Ta;
    double Zk = Z;
    const double dzWay = a * cMcp[2][3];
    if (m_path == CAMERA_STRAIGHT_LINE && Z - dzWay > 0.0) {
      // The pose a of the way is [Rz(-a turn), a d]; a plane parallel to the image at depth Z is seen from it through
      // x' = s R(a turn) x - s R(a turn) a d_xy / Z, s = Z / (Z - a d_z) (normalised coordinates).
      const double th = a * turn, dx = a * cMcp[0][3], dy = a * cMcp[1][3], dz = dzWay;
      const double sc = Z / (Z - dz), ct = std::cos(th), st = std::sin(th);
      Ta = vpMorphRigidTransform(th, -sc * (ct * dx - st * dy) / Z, -sc * (st * dx + ct * dy) / Z, sc, 0.0, 0.0);
      Zk = Z - dz;
    } else { // the image-space way (also when the straight line is no pose in front of the plane)
      Ta = T.interpolated(a, m_longWay);
      Zk = Z / std::pow(T.scale(), a);
    }
    m_goals.push_back(Ta.apply(currentN).toPixels(cam));
    m_depths.push_back(Zk);
    m_maps.push_back(Ta);
  }
  m_rigid = m_goals.size();
  for (const vpMorphContour &d : deformation) {
    m_goals.push_back(d);
    m_depths.push_back(Zd);
    m_maps.push_back(T);
  }
  m_goals.push_back(target);
  m_depths.push_back(Zd);
  m_maps.push_back(T);
}
