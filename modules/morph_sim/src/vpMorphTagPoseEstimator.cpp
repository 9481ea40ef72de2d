#include <visp3/morph_sim/vpMorphTagPoseEstimator.h>
#include <visp3/morph_sim/vpMorphThreadCpuClock.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <sstream>

#include <Eigen/Dense>

#include <visp3/core/vpPixelMeterConversion.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/detection/vpDetectorAprilTag.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/vision/vpPose.h>

struct vpMorphTagPoseEstimator::Detector
{
  std::mutex mutex;
  vpDetectorAprilTag detector{vpDetectorAprilTag::TAG_36h11, vpDetectorAprilTag::HOMOGRAPHY_VIRTUAL_VS};
  Detector()
  {
    // One thread and no decimation: the result must not depend on the machine load (determinism).
    detector.setZAlignedWithCameraAxis(true);
    detector.setAprilTagNbThreads(1);
    detector.setAprilTagQuadDecimate(1.0f);
  }
};

vpMorphTagPoseEstimator::vpMorphTagPoseEstimator(int tagId, double tagSize, const vpHomogeneousMatrix &oMt,
                                                 const vpCameraParameters &cam)
  : m_detector(std::make_shared<Detector>()), m_tagId(tagId), m_tagSize(tagSize), m_oMt(oMt), m_cam(cam)
{
  bool finite = true;
  for (unsigned int i = 0; i < 4; ++i)
    for (unsigned int j = 0; j < 4; ++j)
      finite = finite && std::isfinite(oMt[i][j]);
  if (tagId < 0 || !(tagSize > 0.0) || !std::isfinite(tagSize) || !finite || !oMt.isAnHomogeneousMatrix()) {
    std::ostringstream os;
    os << "vpMorphTagPoseEstimator: needs a tag id >= 0, a positive finite tag size and a valid oMt (id " << tagId
       << ", size " << tagSize << ")";
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
}

bool vpMorphTagPoseEstimator::estimate(const vpImage<unsigned char> &I, vpHomogeneousMatrix &cMo,
                                       std::vector<vpImagePoint> *corners) const
{
  if (I.getWidth() == 0 || I.getHeight() == 0)
    throw vpMorphException(vpMorphException::badImageError, "vpMorphTagPoseEstimator: empty image");
  std::lock_guard<std::mutex> lock(m_detector->mutex);
  vpDetectorAprilTag &detector = m_detector->detector;
  std::vector<vpHomogeneousMatrix> cMt_detector;
  if (!detector.detect(I, m_tagSize, m_cam, cMt_detector))
    return false;
  const std::vector<int> ids = detector.getTagsId();
  for (size_t k = 0; k < ids.size(); ++k) {
    if (ids[k] != m_tagId)
      continue;
    // libapriltag puts pixel centres at half-integers: its corners are +0.5 px from ViSP's convention (the centre
    // of pixel (i, j) at (i, j), as in vpImageSimulator and vpMeterPixelConversion). The pose is computed here
    // from the corrected corners with vpPose (Dementhon or Lagrange, the better, then virtual visual servoing),
    // which also avoids the flipped planar solution the detector's homography can fall into on a small,
    // nearly fronto-parallel tag.
    std::vector<vpImagePoint> ips = detector.getPolygon(k);
    if (ips.size() != 4)
      continue;
    const double h = m_tagSize / 2;
    const double X[4] = {-h, h, h, -h}, Y[4] = {h, h, -h, -h}; // the detector's corner order, z into the tag
    vpPose pose;
    for (size_t c = 0; c < 4; ++c) {
      ips[c].set_uv(ips[c].get_u() - 0.5, ips[c].get_v() - 0.5);
      vpPoint P(X[c], Y[c], 0.0);
      double x = 0.0, y = 0.0;
      vpPixelMeterConversion::convertPoint(m_cam, ips[c], x, y);
      P.set_x(x);
      P.set_y(y);
      pose.addPoint(P);
    }
    vpHomogeneousMatrix cMt_d, cMt_l, cMt;
    pose.computePose(vpPose::DEMENTHON, cMt_d);
    pose.computePose(vpPose::LAGRANGE, cMt_l);
    cMt = pose.computeResidual(cMt_d) < pose.computeResidual(cMt_l) ? cMt_d : cMt_l;
    pose.computePose(vpPose::VIRTUAL_VS, cMt);
    cMo = cMt * m_oMt.inverse();
    if (corners)
      *corners = ips;
    return true;
  }
  return false;
}

void vpMorphTagPoseEstimator::poseDifference(const vpHomogeneousMatrix &aMo, const vpHomogeneousMatrix &bMo,
                                             double &translation, double &rotation)
{
  translation = (aMo.getTranslationVector() - bMo.getTranslationVector()).frobeniusNorm();
  const vpThetaUVector tu(aMo.getRotationMatrix() * bMo.getRotationMatrix().inverse());
  rotation = std::sqrt(tu[0] * tu[0] + tu[1] * tu[1] + tu[2] * tu[2]);
}

namespace
{
// \e extract applied to \e I with the tag masked; \e empty when the extractor finds no object.
template <typename T, typename F>
T extractMasked(const vpImage<unsigned char> &I, const std::vector<vpImagePoint> &corners, double *extractionMs,
                F extract)
{
  vpImage<unsigned char> J = I;
  if (corners.size() == 4)
    vpMorphTagPoseEstimator::maskTag(J, corners);
  const vpMorphThreadCpuClock::time_point t0 = vpMorphThreadCpuClock::now();
  T out;
  try {
    out = extract(J);
  } catch (const vpMorphException &e) {
    if (e.getCode() != vpMorphException::badImageError)
      throw;
    out = T(); // no object in the image
  }
  if (extractionMs)
    *extractionMs = vpMorphThreadCpuClock::millisecondsSince(t0);
  return out;
}
} // namespace

vpMorphContour vpMorphTagPoseEstimator::silhouette(const vpImage<unsigned char> &I,
                                                   const std::vector<vpImagePoint> &corners, double *extractionMs)
{
  return silhouette(I, corners, vpMorphContour(), extractionMs);
}

vpMorphContour vpMorphTagPoseEstimator::silhouette(const vpImage<unsigned char> &I,
                                                   const std::vector<vpImagePoint> &corners,
                                                   const vpMorphContour &previous, double *extractionMs)
{
  return extractMasked<vpMorphContour>(I, corners, extractionMs, [&previous](const vpImage<unsigned char> &J) {
    return vpMorphContourExtractor().extractJoined(J, previous);
  });
}

std::vector<vpMorphContour> vpMorphTagPoseEstimator::silhouetteCandidates(const vpImage<unsigned char> &I,
                                                                        const std::vector<vpImagePoint> &corners,
                                                                        double *extractionMs)
{
  return extractMasked<std::vector<vpMorphContour> >(
      I, corners, extractionMs,
      [](const vpImage<unsigned char> &J) { return vpMorphContourExtractor().extractCandidates(J); });
}

void vpMorphTagPoseEstimator::maskTag(vpImage<unsigned char> &I, const std::vector<vpImagePoint> &corners,
                                      double margin)
{
  if (corners.size() != 4 || !std::isfinite(margin) || margin < 0.0)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphTagPoseEstimator::maskTag: 4 corners and a non-negative margin are needed");
  double cu = 0, cv = 0;
  for (const vpImagePoint &c : corners) {
    cu += c.get_u() / 4;
    cv += c.get_v() / 4;
  }
  // The black square is 8 of the 10 cells of the texture; the outer cell is the white quiet zone, already at the
  // plane's level. Paint the black square grown by the margin only: the quiet zone may touch the object, and
  // painting it would eat into the silhouette. The fill level is read in the middle of the quiet zone (9/8).
  std::vector<double> u(4), v(4), ru(4), rv(4);
  for (size_t k = 0; k < 4; ++k) {
    const double du = corners[k].get_u() - cu, dv = corners[k].get_v() - cv, d = std::hypot(du, dv);
    const double g = d > 0 ? (d + margin * std::sqrt(2.0)) / d : 1.0;
    u[k] = cu + g * du;
    v[k] = cv + g * dv;
    ru[k] = cu + 1.125 * du;
    rv[k] = cv + 1.125 * dv;
  }
  auto inside = [&](double pu, double pv) {
    bool in = false;
    for (size_t i = 0, j = 3; i < 4; j = i++)
      if ((v[i] > pv) != (v[j] > pv) && pu < (u[j] - u[i]) * (pv - v[i]) / (v[j] - v[i]) + u[i])
        in = !in;
    return in;
  };
  // Fill level: the plane's, read on the quiet zone's middle line, a median per side (the object crossing part of a
  // side does not count) at the side's middle; the plane through those carries the light's fall-off under the tag,
  // a single median when fewer than 3 sides are in the image.
  std::vector<unsigned char> all;
  Eigen::MatrixXd A(0, 3);
  Eigen::VectorXd b(0);
  for (size_t k = 0; k < 4; ++k) {
    const size_t l = (k + 1) % 4;
    const int n = std::max(1, static_cast<int>(std::hypot(ru[l] - ru[k], rv[l] - rv[k])));
    std::vector<unsigned char> side;
    for (int i = 0; i < n; ++i) {
      const double pu = ru[k] + (ru[l] - ru[k]) * i / n, pv = rv[k] + (rv[l] - rv[k]) * i / n;
      if (pu >= 0 && pv >= 0 && pu < I.getWidth() - 0.5 && pv < I.getHeight() - 0.5)
        side.push_back(I[static_cast<unsigned int>(pv + 0.5)][static_cast<unsigned int>(pu + 0.5)]);
    }
    if (side.empty())
      continue;
    all.insert(all.end(), side.begin(), side.end());
    std::nth_element(side.begin(), side.begin() + side.size() / 2, side.end());
    A.conservativeResize(A.rows() + 1, 3);
    b.conservativeResize(b.rows() + 1);
    A.row(A.rows() - 1) << 1.0, 0.5 * (ru[k] + ru[l]) - cu, 0.5 * (rv[k] + rv[l]) - cv;
    b(b.rows() - 1) = side[side.size() / 2];
  }
  if (all.empty())
    return; // the whole tag region is outside the image
  std::nth_element(all.begin(), all.begin() + all.size() / 2, all.end());
  Eigen::Vector3d plane(all[all.size() / 2], 0.0, 0.0);
  if (A.rows() >= 3) {
    const Eigen::Vector3d p = A.colPivHouseholderQr().solve(b);
    if (p.allFinite())
      plane = p;
  }
  auto fill = [&](double pu, double pv) {
    return static_cast<unsigned char>(
        std::min(255.0, std::max(0.0, std::round(plane(0) + plane(1) * (pu - cu) + plane(2) * (pv - cv)))));
  };
  const double umin = std::max(0.0, *std::min_element(u.begin(), u.end()));
  const double umax = std::min(I.getWidth() - 1.0, *std::max_element(u.begin(), u.end()));
  const double vmin = std::max(0.0, *std::min_element(v.begin(), v.end()));
  const double vmax = std::min(I.getHeight() - 1.0, *std::max_element(v.begin(), v.end()));
  for (unsigned int pv = static_cast<unsigned int>(std::floor(vmin));
       pv <= static_cast<unsigned int>(std::ceil(vmax)) && pv < I.getHeight(); ++pv)
    for (unsigned int pu = static_cast<unsigned int>(std::floor(umin));
         pu <= static_cast<unsigned int>(std::ceil(umax)) && pu < I.getWidth(); ++pu)
      if (inside(pu, pv))
        I[pv][pu] = fill(pu, pv);
}
