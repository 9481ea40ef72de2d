#include <visp3/morph_sim/vpMorphTagPoseEstimator.h>

#include <cmath>
#include <sstream>

#include <visp3/core/vpPixelMeterConversion.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/detection/vpDetectorAprilTag.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/vision/vpPose.h>

vpMorphTagPoseEstimator::vpMorphTagPoseEstimator(int tagId, double tagSize, const vpHomogeneousMatrix &oMt,
                                                 const vpCameraParameters &cam)
  : m_tagId(tagId), m_tagSize(tagSize), m_oMt(oMt), m_cam(cam)
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
  // One thread and no decimation: the result must not depend on the machine load (determinism).
  vpDetectorAprilTag detector(vpDetectorAprilTag::TAG_36h11, vpDetectorAprilTag::HOMOGRAPHY_VIRTUAL_VS);
  detector.setZAlignedWithCameraAxis(true);
  detector.setAprilTagNbThreads(1);
  detector.setAprilTagQuadDecimate(1.0f);
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
