// The stock adapters of vpMorphBenchController: IBVS on the tag corners, PBVS on the tag pose, moment-based servoing
// on the silhouette.
#include "vpMorphBenchAdapter.h"

#include <cmath>

#include <visp3/core/vpMomentCommon.h>
#include <visp3/core/vpMomentObject.h>
#include <visp3/core/vpPlane.h>
#include <visp3/core/vpVelocityTwistMatrix.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/visual_features/vpFeatureBuilder.h>
#include <visp3/visual_features/vpFeatureMomentCommon.h>
#include <visp3/visual_features/vpFeaturePoint.h>
#include <visp3/visual_features/vpFeatureThetaU.h>
#include <visp3/visual_features/vpFeatureTranslation.h>
#include <visp3/vs/vpServo.h>

namespace
{
//! Plane 1/Z = A x + B y + C of the object plane (z = 0 of the object frame) seen from cMo.
void planeOf(const vpHomogeneousMatrix &cMo, double &A, double &B, double &C)
{
  vpPlane pl(0, 0, 1, 0);
  pl.changeFrame(cMo);
  if (std::fabs(pl.getD()) < 1e-12) {
    A = B = 0;
    C = 1;
    return;
  }
  A = -pl.getA() / pl.getD();
  B = -pl.getB() / pl.getD();
  C = -pl.getC() / pl.getD();
}

//! IBVS on the 4 tag corners (ViSP's tutorial-ibvs-4pts set-up), depth of each corner from the tag pose.
class IbvsController : public vpMorphBenchAdapter
{
public:
  IbvsController(vpServo::vpServoIteractionMatrixType L, const char *name) : m_L(L), m_name(name) {}
  std::string name() const override { return m_name; }
  Command step(const vpImage<unsigned char> &I, const vpMatrix &eJe, const vpColVector &) override
  {
    const Clock::time_point t0 = Clock::now();
    const TagView tag = detectTag(I);
    if (!tag.found || tag.corners.size() != 4)
      return holdCommand(msSince(t0));
    for (unsigned int i = 0; i < 4; ++i) {
      vpFeatureBuilder::create(m_p[i], m_ctx.cam, tag.corners[i]);
      vpPoint P = m_ctx.tagCorners3D[i];
      P.track(tag.cMo);
      m_p[i].set_Z(P.get_Z());
    }
    Command cmd = stockLaw(*m_task, eJe, msSince(t0));
    // Stop rule: the corners' RMS displacement (px) to their taught places.
    const vpColVector e = m_task->getError();
    double sum = 0.0;
    for (unsigned int i = 0; i < 4; ++i)
      sum += std::pow(e[2 * i] * m_ctx.cam.get_px(), 2) + std::pow(e[2 * i + 1] * m_ctx.cam.get_py(), 2);
    cmd.converged = !cmd.stop && settled(std::sqrt(sum / 4), cornerNoisePx(taughtTagSidePx()));
    return cmd;
  }

private:
  void reset() override
  {
    m_task.reset(new vpServo);
    setupStockTask(*m_task, m_L);
    if (m_ctx.taughtTagCorners.size() != 4)
      throw vpMorphException(vpMorphException::badParameterError, m_name + ": the taught view has no 4 tag corners");
    for (unsigned int i = 0; i < 4; ++i) {
      // Teach by showing: the corners detected in the taught view, their depth from the pose estimated there.
      vpFeatureBuilder::create(m_pd[i], m_ctx.cam, m_ctx.taughtTagCorners[i]);
      vpPoint P = m_ctx.tagCorners3D[i];
      P.track(m_ctx.taughtTagPose);
      m_pd[i].set_Z(P.get_Z());
      m_p[i] = m_pd[i]; // replaced at the first measurement; needed for DESIRED and MEAN L before it
      m_task->addFeature(m_p[i], m_pd[i]);
    }
  }
  vpServo::vpServoIteractionMatrixType m_L;
  std::string m_name;
  vpFeaturePoint m_p[4], m_pd[4];
  std::unique_ptr<vpServo> m_task;
};

//! PBVS on the tag pose (ViSP's tutorial-pbvs set-up: t = cdMc translation, theta-u of cdRc, both to zero).
class PbvsController : public vpMorphBenchAdapter
{
public:
  std::string name() const override { return "pbvs"; }
  Command step(const vpImage<unsigned char> &I, const vpMatrix &eJe, const vpColVector &) override
  {
    const Clock::time_point t0 = Clock::now();
    const TagView tag = detectTag(I);
    if (!tag.found)
      return holdCommand(msSince(t0));
    const vpHomogeneousMatrix cdMc = m_ctx.taughtTagPose * tag.cMo.inverse(); // both measured by the detector
    m_t.buildFrom(cdMc);
    m_tu.buildFrom(cdMc);
    Command cmd = stockLaw(*m_task, eJe, msSince(t0));
    // Stop rule: the pose error as the tag corners' RMS displacement (px) between the current and the taught pose.
    double sum = 0.0;
    for (const vpPoint &corner : m_ctx.tagCorners3D) {
      vpPoint a = corner, b = corner;
      a.track(tag.cMo);
      b.track(m_ctx.taughtTagPose);
      sum += std::pow((a.get_x() - b.get_x()) * m_ctx.cam.get_px(), 2) +
             std::pow((a.get_y() - b.get_y()) * m_ctx.cam.get_py(), 2);
    }
    cmd.converged = !cmd.stop && settled(std::sqrt(sum / m_ctx.tagCorners3D.size()), cornerNoisePx(taughtTagSidePx()));
    return cmd;
  }

private:
  void reset() override
  {
    m_task.reset(new vpServo);
    setupStockTask(*m_task, vpServo::CURRENT);
    m_t = vpFeatureTranslation(vpFeatureTranslation::cdMc);
    m_tu = vpFeatureThetaU(vpFeatureThetaU::cdRc);
    m_td = vpFeatureTranslation(vpFeatureTranslation::cdMc);
    m_tud = vpFeatureThetaU(vpFeatureThetaU::cdRc);
    m_td.buildFrom(vpHomogeneousMatrix());
    m_tud.buildFrom(vpHomogeneousMatrix());
    m_task->addFeature(m_t, m_td);
    m_task->addFeature(m_tu, m_tud);
  }
  vpFeatureTranslation m_t, m_td;
  vpFeatureThetaU m_tu, m_tud;
  std::unique_ptr<vpServo> m_task;
};

/*!
  Moment-based servoing on the silhouette (ViSP's servoMomentPolygon set-up: vpMomentCommon with the desired
  surface, mu3 and alpha references, current L), the desired moments from the taught template, the plane of the
  interaction matrix from the tag pose.
  - The moments are those of the measured edge outline (to a few hundredths of a pixel, see fill()), not of the
    polygon that approximates it: the polygon's vertices move from one image to the next, and their moments keep the
    loop wandering about the goal (\ref page_benchmark_history).
  - "moments": ViSP's six features, xn, yn, an, c-invariants sx and sy, alpha, on the six degrees of freedom
    (EYEINHAND_L_cVe_eJe). On a thin object the c-invariants barely depend on the tilt (singular values of L down to
    0.003 on the pliers), and the pseudo-inverse commands metres per second from the first image.
  - "moments-planar": xn, yn, an and alpha on the camera's planar motions (vx, vy, vz, wz; EYEINHAND_CAMERA with
    the tilts disabled, then the estimated eMc, as "morph-vpservo"): the decoupled choice of Tahri and Chaumette for
    a camera parallel to the plane, which is what every set but 6dof starts from.
*/
class MomentsController : public vpMorphBenchAdapter
{
public:
  explicit MomentsController(bool planar = false) : m_planar(planar) {}
  std::string name() const override { return m_planar ? "moments-planar" : "moments"; }
  Command step(const vpImage<unsigned char> &I, const vpMatrix &eJe, const vpColVector &) override
  {
    const TagView tag = detectTag(I);
    double ms = 0;
    const vpMorphContour c = vpMorphTagPoseEstimator::silhouette(I, tag.corners, &ms);
    if (c.empty())
      return holdCommand(ms);
    const Clock::time_point t0 = Clock::now();
    Command cmd;
    try {
      fill(m_obj, c.toNormalized(m_ctx.cam));
      cmd.measureMs = ms + msSince(t0);
      const Clock::time_point t1 = Clock::now();
      double A = 0, B = 0, C = 1.0 / m_ctx.cdMo[2][3];
      if (tag.found)
        planeOf(tag.cMo, A, B, C);
      m_moments->updateAll(m_obj);
      m_features->updateAll(A, B, C);
      if (m_planar) {
        cmd.v = vpVelocityTwistMatrix(m_ctx.eMc) * m_task->computeControlLaw();
        cmd.frame = vpRobot::END_EFFECTOR_FRAME;
      } else {
        m_task->set_eJe(eJe);
        cmd.v = m_task->computeControlLaw();
        cmd.frame = vpRobot::JOINT_STATE;
      }
      cmd.controlMs = msSince(t1);
      // Stop rule on the planar components (the c-invariants have no image displacement of their own): xn, yn are
      // the centroid times the depth, an the depth, alpha the orientation.
      const vpColVector e = m_task->getError();
      const double Zd = m_ctx.cdMo[2][3], r = radiusPx(c), ealpha = e[e.size() - 1];
      cmd.converged =
          settled(std::sqrt(std::pow(e[0] / Zd * m_ctx.cam.get_px(), 2) + std::pow(e[1] / Zd * m_ctx.cam.get_py(), 2) +
                            r * r * (std::pow(e[2] / Zd, 2) + ealpha * ealpha)),
                  outlineNoisePx(c.outline().size()));
    } catch (const vpException &) {
      return stopCommand("feature-error");
    }
    if (!finite(cmd.v))
      return stopCommand("nan");
    return cmd;
  }

private:
  /*!
    The measured outline of \e normalized (its polygon when it has none) as a closed polygon of kMomentPoints equally
    spaced vertices for vpMomentObject, counter-clockwise in the moment sense (positive m00). Oriented before the
    moments are computed: ViSP's dense-polygon moments to order 6 cost about 15 us per vertex (128 vertices: 2 ms;
    the whole outline, a point per boundary pixel: 15-20 ms), and 128 vertices, every 4 px or so on these objects,
    leave the final errors where the whole outline's are (\ref page_benchmark_history).
  */
  static void fill(vpMomentObject &obj, const vpMorphContour &normalized)
  {
    const vpMorphContour c = normalized.outline().resampled(kMomentPoints);
    const std::size_t n = c.size();
    const bool ccw = c.signedArea() >= 0.0; // m00's sign: the same shoelace sum
    std::vector<vpPoint> pts(n + 1);
    for (std::size_t i = 0; i <= n; ++i) {
      const std::size_t k = ccw ? i % n : (n - i) % n;
      pts[i].set_x(c.x(k));
      pts[i].set_y(c.y(k));
    }
    obj.fromVector(pts);
  }
  void reset() override
  {
    if (!m_ctx.database)
      throw vpMorphException(vpMorphException::badParameterError, "moments controller: no template database");
    // The desired silhouette: the taught view of the object present (moments do no recognition).
    const vpMorphTemplate &t = (*m_ctx.database)[m_ctx.expectedObject];
    m_objD.setType(vpMomentObject::DENSE_POLYGON);
    m_obj.setType(vpMomentObject::DENSE_POLYGON);
    fill(m_objD, t.contour().toNormalized(m_ctx.cam));
    const double Zd = m_ctx.cdMo[2][3];
    m_task.reset();
    m_features.reset();
    m_featuresD.reset();
    m_moments.reset(new vpMomentCommon(vpMomentCommon::getSurface(m_objD), vpMomentCommon::getMu3(m_objD),
                                       vpMomentCommon::getAlpha(m_objD), Zd));
    m_momentsD.reset(new vpMomentCommon(vpMomentCommon::getSurface(m_objD), vpMomentCommon::getMu3(m_objD),
                                        vpMomentCommon::getAlpha(m_objD), Zd));
    m_features.reset(new vpFeatureMomentCommon(*m_moments));
    m_featuresD.reset(new vpFeatureMomentCommon(*m_momentsD));
    m_moments->updateAll(m_objD); // until the first measurement
    m_momentsD->updateAll(m_objD);
    m_features->updateAll(0, 0, 1.0 / Zd);
    m_featuresD->updateAll(0, 0, 1.0 / Zd);
    m_task.reset(new vpServo);
    if (m_planar)
      setupPlanarTask(*m_task);
    else
      setupStockTask(*m_task, vpServo::CURRENT);
    m_task->addFeature(m_features->getFeatureGravityNormalized(), m_featuresD->getFeatureGravityNormalized());
    m_task->addFeature(m_features->getFeatureAn(), m_featuresD->getFeatureAn());
    if (!m_planar)
      m_task->addFeature(m_features->getFeatureCInvariant(), m_featuresD->getFeatureCInvariant(),
                         (1 << 10) | (1 << 11));
    m_task->addFeature(m_features->getFeatureAlpha(), m_featuresD->getFeatureAlpha());
  }
  static constexpr std::size_t kMomentPoints = 128;
  bool m_planar;
  vpMomentObject m_obj{6}, m_objD{6};
  std::unique_ptr<vpMomentCommon> m_moments, m_momentsD;
  std::unique_ptr<vpFeatureMomentCommon> m_features, m_featuresD;
  std::unique_ptr<vpServo> m_task;
};
} // namespace

std::unique_ptr<vpMorphBenchController> vpMorphBenchAdapter::createStock(const std::string &name)
{
  if (name == "ibvs-current")
    return std::unique_ptr<vpMorphBenchController>(new IbvsController(vpServo::CURRENT, "ibvs-current"));
  if (name == "ibvs-desired")
    return std::unique_ptr<vpMorphBenchController>(new IbvsController(vpServo::DESIRED, "ibvs-desired"));
  if (name == "ibvs-mean")
    return std::unique_ptr<vpMorphBenchController>(new IbvsController(vpServo::MEAN, "ibvs-mean"));
  if (name == "pbvs")
    return std::unique_ptr<vpMorphBenchController>(new PbvsController);
  if (name == "moments")
    return std::unique_ptr<vpMorphBenchController>(new MomentsController);
  if (name == "moments-planar")
    return std::unique_ptr<vpMorphBenchController>(new MomentsController(true));
  return nullptr;
}
