#include <visp3/morph_bench/vpMorphBenchController.h>

#include <algorithm>
#include <cmath>

#include <visp3/core/vpMomentCommon.h>
#include <visp3/core/vpMomentObject.h>
#include <visp3/core/vpPlane.h>
#include <visp3/core/vpVelocityTwistMatrix.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph_sim/vpMorphTagPoseEstimator.h>
#include <visp3/morph_sim/vpMorphThreadCpuClock.h>
#include <visp3/morph_vs/vpFeatureMorph.h>
#include <visp3/morph_vs/vpMorphJointVelocity.h>
#include <visp3/morph_vs/vpServoMorph.h>
#include <visp3/visual_features/vpFeatureBuilder.h>
#include <visp3/visual_features/vpFeatureMomentCommon.h>
#include <visp3/visual_features/vpFeaturePoint.h>
#include <visp3/visual_features/vpFeatureThetaU.h>
#include <visp3/visual_features/vpFeatureTranslation.h>
#include <visp3/vs/vpServo.h>

namespace
{
// Compute times are the CPU time of the run's thread: starts run on every core (see vpMorphThreadCpuClock).
using Clock = vpMorphThreadCpuClock;
double msSince(Clock::time_point t0) { return Clock::millisecondsSince(t0); }

//! The tag seen in an image: its pose (from the estimated intrinsics) and its corners.
struct TagView
{
  bool found = false;
  vpHomogeneousMatrix cMo;
  std::vector<vpImagePoint> corners;
};

TagView detectTag(const vpMorphTagPoseEstimator &est, const vpImage<unsigned char> &I)
{
  TagView t;
  t.found = est.estimate(I, t.cMo, &t.corners);
  return t;
}

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

bool finite(const vpColVector &v)
{
  for (unsigned int i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]))
      return false;
  return true;
}

//! Common part of every adapter: the context and the tag estimator built with the estimated intrinsics.
class Base : public vpMorphBenchController
{
public:
  void start(const Context &ctx) override
  {
    m_ctx = ctx;
    m_tag.reset(new vpMorphTagPoseEstimator(ctx.tagId, ctx.tagSize, ctx.oMt, ctx.cam));
    m_settled = 0;
    reset();
  }

protected:
  /*!
    The adapters' stop rule on their own error (Command::converged; vpServoMorph has its own, CONVERGED): the error
    norm, as the RMS image displacement (px) of the points the feature stands for, within 3 times its own noise on
    kConvergedPeriods successive measured periods: below that the error is the measurement's noise. Its noise comes
    from sigma = 0.1 px per edge point (vpMorphBenchObservability's noise model) through the feature's fit:
    - a fit of a similarity (4 parameters) to n outline points moves them by sigma sqrt(4 / n) RMS (outlineNoisePx());
    - a tag corner, where two edges of L pixels fitted by least squares meet, by 2 sigma / sqrt(L) (cornerNoisePx()).
  */
  static constexpr double kEdgeNoisePx = 0.1;
  static constexpr unsigned int kConvergedPeriods = 3;
  static double outlineNoisePx(std::size_t points)
  {
    return kEdgeNoisePx * std::sqrt(4.0 / std::max<std::size_t>(points, 4));
  }
  static double cornerNoisePx(double edgePx) { return 2.0 * kEdgeNoisePx / std::sqrt(std::max(edgePx, 1.0)); }
  //! Counts a period whose error norm is \e rmsPx against the noise \e noisePx; true once the rule holds.
  bool settled(double rmsPx, double noisePx)
  {
    m_settled = std::isfinite(rmsPx) && rmsPx <= 3.0 * noisePx ? m_settled + 1 : 0;
    return m_settled >= kConvergedPeriods;
  }
  //! Mean side (px) of the tag's taught corners: the length of the edges its corners are fitted on.
  double taughtTagSidePx() const
  {
    const std::vector<vpImagePoint> &c = m_ctx.taughtTagCorners;
    double sum = 0.0;
    for (std::size_t i = 0; i < c.size(); ++i)
      sum += vpImagePoint::distance(c[i], c[(i + 1) % c.size()]);
    return c.empty() ? 0.0 : sum / c.size();
  }
  //! RMS distance (px) of the contour's points to their centroid: what a rotation or scale error moves them by.
  static double radiusPx(const vpMorphContour &c)
  {
    double cx = 0.0, cy = 0.0, r2 = 0.0;
    c.centroid(cx, cy);
    for (std::size_t k = 0; k < c.size(); ++k)
      r2 += (c.x(k) - cx) * (c.x(k) - cx) + (c.y(k) - cy) * (c.y(k) - cy);
    return c.size() ? std::sqrt(r2 / c.size()) : 0.0;
  }
  virtual void reset() = 0;
  //! A stock vpServo set up as ViSP's examples do for a robot arm: eye-in-hand, L cVe eJe, constant gain.
  void setupStockTask(vpServo &task, vpServo::vpServoIteractionMatrixType L) const
  {
    task.setServo(vpServo::EYEINHAND_L_cVe_eJe);
    task.setInteractionMatrixType(L, vpServo::PSEUDO_INVERSE);
    task.set_cVe(vpVelocityTwistMatrix(m_ctx.eMc.inverse()));
    task.setLambda(m_ctx.lambda);
  }
  /*!
    A stock vpServo on the camera's planar motions (vx, vy, vz, wz): EYEINHAND_CAMERA, current L, the tilts disabled
    (setCameraDoF), the same gain; the adapter maps its camera velocity with the estimated eMc.
  */
  void setupPlanarTask(vpServo &task) const
  {
    task.setServo(vpServo::EYEINHAND_CAMERA);
    task.setInteractionMatrixType(vpServo::CURRENT, vpServo::PSEUDO_INVERSE);
    task.setLambda(m_ctx.lambda);
    vpColVector dof(6, 1.0);
    dof[3] = dof[4] = 0; // no tilt
    task.setCameraDoF(dof);
  }
  /*!
    The stock task's joint velocity for the features just measured (in \e measureMs), with the time of the law;
    a stop instead of a non-finite command.
  */
  static Command stockLaw(vpServo &task, const vpMatrix &eJe, double measureMs)
  {
    Command cmd;
    cmd.measureMs = measureMs;
    const Clock::time_point t0 = Clock::now();
    task.set_eJe(eJe);
    cmd.v = task.computeControlLaw();
    cmd.controlMs = msSince(t0);
    cmd.frame = vpRobot::JOINT_STATE;
    if (!finite(cmd.v))
      return stopCommand("nan");
    return cmd;
  }
  static Command holdCommand(double measureMs)
  {
    Command c;
    c.measured = false;
    c.measureMs = measureMs;
    return c;
  }
  static Command stopCommand(const std::string &reason)
  {
    Command c;
    c.stop = true;
    c.reason = reason;
    return c;
  }

  Context m_ctx;
  std::unique_ptr<vpMorphTagPoseEstimator> m_tag;
  unsigned int m_settled = 0;
};

//! Recognition at the first frame, the target check and the re-recognition, shared by the two VISPMorph adapters.
class MorphBase : public Base
{
public:
  std::string recognizedObject() const override { return m_object; }

protected:
  //! Factor on a template's acceptance threshold for vpServoMorph's own target check: a slack over recognition's
  //! threshold, as a view seen during the servo is not the first view (a last line of defence, see mismatch()).
  static constexpr double kCheckSlack = 1.25;
  //! The recognition is checked on the first image and then every kCheckPeriod measured images (1 s at 25 Hz).
  static constexpr unsigned int kCheckPeriod = 25;
  //! Another template replaces the current one only when the current one costs this much more work.
  static constexpr double kSwitchRatio = 1.2; // vpMorphServoGuard::getMismatchRatio()

  /*!
    The silhouette of image \e I and, on the first one, the recognition. False when the caller must return
    \e cmd as it is (hold: no silhouette; stop: rejected); true with cmd.measureMs set.
  */
  bool observe(const vpImage<unsigned char> &I, vpMorphContour &c, Command &cmd)
  {
    double ms = 0;
    const TagView tag = detectTag(*m_tag, I);
    c = vpMorphTagPoseEstimator::silhouette(I, tag.corners, &ms);
    if (c.empty()) {
      cmd = holdCommand(ms);
      return false;
    }
    std::string reason;
    if (!recognize(c, reason)) {
      cmd = stopCommand(reason);
      return false;
    }
    cmd = Command();
    cmd.measureMs = ms;
    return true;
  }
  //! Recognises the object on the first contour; returns false (and sets \e reason) if it is rejected.
  bool recognize(const vpMorphContour &c, std::string &reason)
  {
    if (m_template)
      return true;
    if (!m_ctx.database || m_ctx.database->empty())
      throw vpMorphException(vpMorphException::badParameterError, "morph controller: no template database");
    if (!m_ctx.forcedTemplate.empty()) { // fault injection: a recognition error
      m_template = &(*m_ctx.database)[m_ctx.forcedTemplate];
      m_object = m_template->name();
      return true;
    }
    const vpMorphRecognition r = m_ctx.database->recognize(c);
    if (r.index == vpMorphRecognition::npos || !r.accepted) {
      reason = "recognition";
      return false;
    }
    m_template = &(*m_ctx.database)[r.index];
    m_object = m_template->name();
    return true;
  }
  /*!
    True when \e c is not the current template's shape (vpServoMorph's target check, for the adapter without
    vpServoMorph): not accepted by the database as that template with kCheckSlack (vpMorphDatabase::accepts():
    beyond its threshold times kCheckSlack, and not an occluded view of it), or the database clearly prefers
    another template (its best, accepted, at least kSwitchRatio times cheaper). The thresholds alone cannot
    tell every pair apart: calibrated on 20 % occlusions, the pliers' threshold (1.57) is above its distance to
    the screwdriver (1.44), so a screwdriver taken for the pliers passes it.
  */
  bool mismatch(const vpMorphContour &c) const
  {
    const vpMorphDatabase &db = *m_ctx.database;
    const std::size_t cur = db.find(m_template->name());
    const vpMorphRecognition r = db.recognize(c);
    if (r.index == vpMorphRecognition::npos || r.index == cur)
      return false;
    double d = 0.0;
    return !db.accepts(c, cur, kCheckSlack, &d) || (r.accepted && d >= kSwitchRatio * r.distance);
  }
  /*!
    The current template was found wrong for \e c: recognises \e c again without the templates already
    rejected (the best, else the runner-up, if the database accepts it). False when none is left.
  */
  bool rerecognize(const vpMorphContour &c)
  {
    const vpMorphDatabase &db = *m_ctx.database;
    m_rejected.push_back(db.find(m_template->name()));
    const vpMorphRecognition r = db.recognize(c);
    const std::size_t idx[2] = {r.index, r.secondIndex};
    for (int k = 0; k < 2; ++k) {
      if (idx[k] == vpMorphRecognition::npos ||
          std::find(m_rejected.begin(), m_rejected.end(), idx[k]) != m_rejected.end() ||
          !(k == 0 ? r.accepted : db.accepts(c, idx[k])))
        continue;
      m_template = &db[idx[k]];
      m_object = m_template->name();
      return true;
    }
    return false;
  }
  void reset() override
  {
    m_template = nullptr;
    m_object.clear();
    m_rejected.clear();
  }

  const vpMorphTemplate *m_template = nullptr;
  std::string m_object;
  std::vector<std::size_t> m_rejected;
};

/*!
  VISPMorph's controller: vpServoMorph through 10 sub-goals, Eq. 5-11, online hand-eye estimation, and the
  out-of-plane (tilt) correction on the final approach (vpServoMorph::TILT_FINAL_APPROACH: the contour's homography
  refined on the measured edge outlines, default dead zones), first turning the camera by kExplorationDeg about its
  optical axis and back to read the tilt of the camera on the hand (vpServoMorph::setHandEyeTiltExploration())
  ("morph"); or the planar law alone, no tilt command and no turn ("morph-planar"); or the paper's method as it is
  written (vpServoMorph::PAPER: elongation-vector rectification over the morph's correspondence, image-space rigid
  frames and deformation frames, the per-axis thresholds; no tilt, no turn: "morph-paper"). All give the servo the
  robot's joints (vpServoMorph::setJointState()), so that a half turn is planned the way that keeps them clear of their
  limits, and send joint velocities from the Jacobian at the middle of each period (vpMorphJointVelocity): held for the
  period from the Jacobian at its start, a turn about the optical axis tilts the Afma6's camera, a tilt the planar law
  does not take back.
*/
class MorphController : public MorphBase
{
  //! The exploration turn (deg): a quarter turn takes the object's long axis from one image axis to the other, so
  //! its views show a tilt of the camera on the hand about any in-plane axis.
  static constexpr double kExplorationDeg = 90.0;

public:
  enum Mode { FULL, PLANAR, PAPER };
  explicit MorphController(Mode mode = FULL)
    : m_tilt(mode == FULL), m_paper(mode == PAPER),
      m_name(mode == FULL ? "morph" : (mode == PLANAR ? "morph-planar" : "morph-paper"))
  {
  }
  std::string name() const override { return m_name; }
  Command step(const vpImage<unsigned char> &I, const vpMatrix &eJe, const vpColVector &q) override
  {
    vpMorphContour c;
    Command cmd;
    if (!observe(I, c, cmd)) {
      if (cmd.measured || !m_targetSet)
        return cmd;                  // a stop, or nothing seen before the first recognition
      Command hold = missingFrame(); // nothing seen: vpServoMorph holds (and stops after too long)
      hold.measureMs = cmd.measureMs;
      return hold;
    }
    if (!m_targetSet) {
      if (m_tilt) // the turn comes back near the image's border: it needs the image's size
        m_servo->getHandEyeExploration().setAngle(vpMath::rad(kExplorationDeg), I.getWidth(), I.getHeight());
      setTarget();
    }
    const Clock::time_point t0 = Clock::now();
    m_servo->getPlanner().setJointState(eJe, q, m_ctx.jointMin, m_ctx.jointMax); // read when a sequence is planned
    cmd.v = m_servo->computeControlLaw(c);
    cmd.controlMs = msSince(t0);
    if (m_servo->getStatus() == vpServoMorph::TARGET_MISMATCH) {
      // vpServoMorph's target check (at each new sequence and before convergence): recognise anew, restart.
      if (!rerecognize(c))
        return stopCommand("target-mismatch");
      setTarget();
      cmd.rerecognized = true;
      cmd.v = m_servo->computeControlLaw(c);
    }
    cmd = fromStatus(cmd);
    const Clock::time_point t1 = Clock::now(); // the joint velocities are part of the law's time
    cmd.v = m_joints.compute(eJe, q, cmd.v);
    cmd.controlMs += msSince(t1);
    cmd.frame = vpRobot::JOINT_STATE;
    return cmd;
  }
  Command missingFrame() override
  {
    if (!m_targetSet)
      return holdCommand(0);
    Command cmd;
    cmd.v = m_servo->computeControlLaw(vpMorphContour()); // hold, counted towards the lost limit
    return fromStatus(cmd);
  }
  const vpServoMorph *servo() const override { return m_servo.get(); }

private:
  void setTarget()
  {
    m_servo->setTarget(*m_template);
    m_servo->getGuard().setTargetCheck(*m_ctx.database, m_template->name(), kCheckSlack);
    m_targetSet = true;
  }
  Command fromStatus(Command cmd) const
  {
    cmd.frame = vpRobot::END_EFFECTOR_FRAME;
    const vpServoMorph::Status s = m_servo->getStatus();
    cmd.converged = s == vpServoMorph::CONVERGED;
    switch (s) {
    case vpServoMorph::TARGET_LOST:
    case vpServoMorph::DEGENERATE_CONTOUR:
    case vpServoMorph::UNEXPLAINED_VIEW:
      cmd.measured = false; // a hold: vpServoMorph stops by itself after too many in a row
      break;
    case vpServoMorph::REPLANNED:
      cmd.replanned = true;
      break;
    case vpServoMorph::NOT_STARTED:
    case vpServoMorph::MOVING:
    case vpServoMorph::SUBGOAL_REACHED:
    case vpServoMorph::CONVERGED:
      break;
    default: {
      // Every other status is a stop with zero velocity (a fault, or "not sure"): a failure with its reason,
      // never a convergence.
      cmd.stop = true;
      std::string r = vpServoMorph::statusName(s);
      std::replace(r.begin(), r.end(), ' ', '-');
      cmd.reason = r;
      break;
    }
    }
    return cmd;
  }
  void reset() override
  {
    MorphBase::reset();
    m_servo.reset(new vpServoMorph);
    if (m_paper)
      m_servo->setMeasurement(vpServoMorph::PAPER);
    m_servo->setCameraParameters(m_ctx.cam);
    m_servo->set_eMc(m_ctx.eMc);
    m_servo->getPlanner().setSubGoalCount(10);
    m_servo->setSamplingTime(m_ctx.samplingTime);
    m_servo->setGain(std::min(1.0, m_ctx.lambda * m_ctx.samplingTime)); // same exponential rate as lambda
    // Extracted contours are digitised: the final residual settles at a few tenths of a pixel.
    // The tilt's own final threshold stays the estimator's default, the same 0.002 rad.
    m_servo->setFinalThresholds(0.002, 0.2);
    // 0.05 % of the depth: a quarter millimetre at 0.5 m (the outlines' scale wanders by about 0.03 % under noise).
    m_servo->setFinalScaleThreshold(5e-4);
    if (m_tilt)
      m_servo->setTiltCorrection(vpServoMorph::TILT_FINAL_APPROACH);
    m_servo->getGuard().setMaxLostIterations(8); // its own stop before the loop's feature-lost (10)
    m_targetSet = false;
    m_joints.setSamplingTime(m_ctx.samplingTime);
    m_joints.reset();
  }

  bool m_tilt, m_paper;
  std::string m_name;
  std::unique_ptr<vpServoMorph> m_servo;
  vpMorphJointVelocity m_joints;
  bool m_targetSet = false;
};

/*!
  vpFeatureMorph in a stock vpServo, to the final goal (no sub-goals): EYEINHAND_CAMERA with the tilt rotations
  disabled (setCameraDoF: the feature has 4 components for a planar task), current L, then the camera velocity
  is mapped to the end-effector with the estimated eMc. The depth comes from the area ratio to the template.
  The target check runs on the first image and every kCheckPeriod measured iterations.
*/
class MorphVpServoController : public MorphBase
{
public:
  std::string name() const override { return "morph-vpservo"; }
  Command step(const vpImage<unsigned char> &I, const vpMatrix &, const vpColVector &) override
  {
    vpMorphContour c;
    Command cmd;
    if (!observe(I, c, cmd))
      return cmd;
    if (m_measured++ % kCheckPeriod == 0 && mismatch(c)) {
      if (!rerecognize(c))
        return stopCommand("target-mismatch");
      cmd.rerecognized = true;
      m_built = false; // a new goal
      m_havePrev = false;
    }
    const Clock::time_point t0 = Clock::now();
    const double Zd = m_template->cdMo()[2][3];
    try {
      if (!m_built) {
        // An articulated template: posed at the opening the view shows (as vpServoMorph does).
        const vpMorphContour goal = m_template->viewFor(c);
        m_sd.buildFrom(goal, m_ctx.cam, Zd);
        m_areaD = goal.area();
      }
      const double a = c.area();
      if (!(a > 25.0))
        return stopCommand("degenerate-contour");
      // The depth of the view: the desired one times the scale the feature's last alignment measured (the area ratio
      // before the first).
      const vpMorphViewAlignment &al = m_s.getAlignment();
      m_s.buildFrom(c, m_ctx.cam, Zd * (m_built && al.explained() ? al.transform.scale() : std::sqrt(m_areaD / a)));
      if (!m_built) {
        m_task.reset(new vpServo);
        setupPlanarTask(*m_task);
        m_task->addFeature(m_s, m_sd);
        m_built = true;
      }
      const vpColVector vc = m_task->computeControlLaw();
      // A view the feature's aligner does not explain gives a zero error: not a goal reached, a view not measured.
      if (!m_s.getAlignment().explained())
        return holdCommand(msSince(t0));
      const vpColVector e = m_task->getError();
      if (errorJumped(e))
        return stopCommand("feature-jump");
      cmd.v = vpVelocityTwistMatrix(m_ctx.eMc) * vc;
      // Stop rule: s - s* = (centroid, angle, log scale) as the outline's RMS displacement in pixels.
      const double r = radiusPx(c);
      cmd.converged = settled(std::sqrt(e[0] * e[0] * m_ctx.cam.get_px() * m_ctx.cam.get_px() +
                                        e[1] * e[1] * m_ctx.cam.get_py() * m_ctx.cam.get_py() +
                                        r * r * (e[2] * e[2] + e[3] * e[3])),
                              outlineNoisePx(c.outline().size()));
    } catch (const vpException &e) {
      return stopCommand("feature-error");
    }
    cmd.controlMs = msSince(t0);
    cmd.frame = vpRobot::END_EFFECTOR_FRAME;
    if (!finite(cmd.v))
      return stopCommand("nan");
    return cmd;
  }
  std::pair<const vpFeatureMorph *, const vpFeatureMorph *> features() const override { return {&m_s, &m_sd}; }

private:
  /*!
    A stock vpServo has no plan to re-make and no test of its own input: a view that jumps (a bump, the camera
    displaced, another shape taken for the object) would drag it anywhere. Its law makes each component of the error
    e = s - s* (centroid, angle, log scale) decrease by lambda dt of itself per period (L L+ = I for four features on
    four motions); a change of a component beyond twice that, plus 15 px, 2 deg or 5 % in scale (the bump the adapter
    detects), is a jump, and the adapter stops ("feature-jump") before sending the command. On the error, where the
    law's prediction holds, rather than on the fit's parameters, whose translation about the view's centroid moves
    with the rotation.
  */
  bool errorJumped(const vpColVector &e)
  {
    const double g = m_ctx.lambda * m_ctx.samplingTime;
    const double bump[4] = {15.0 / m_ctx.cam.get_px(), 15.0 / m_ctx.cam.get_py(), vpMath::rad(2.0), 0.05};
    bool jump = false;
    if (m_havePrev)
      for (unsigned int i = 0; i < 4 && !jump; ++i) {
        const double change = i == 2 ? std::remainder(e[i] - m_prevError[i], 2.0 * M_PI) : e[i] - m_prevError[i];
        jump = std::fabs(change + g * m_prevError[i]) > g * std::fabs(m_prevError[i]) + bump[i];
      }
    m_prevError = e;
    m_havePrev = true;
    return jump;
  }
  void reset() override
  {
    MorphBase::reset();
    m_havePrev = false;
    m_task.reset();
    m_s = vpFeatureMorph();
    m_sd = vpFeatureMorph();
    m_built = false;
    m_measured = 0;
  }
  vpFeatureMorph m_s, m_sd;
  std::unique_ptr<vpServo> m_task;
  double m_areaD = 0;
  bool m_built = false;
  unsigned int m_measured = 0;
  bool m_havePrev = false;
  vpColVector m_prevError; // the task's error at the last period
};

//! IBVS on the 4 tag corners (ViSP's tutorial-ibvs-4pts set-up), depth of each corner from the tag pose.
class IbvsController : public Base
{
public:
  IbvsController(vpServo::vpServoIteractionMatrixType L, const char *name) : m_L(L), m_name(name) {}
  std::string name() const override { return m_name; }
  Command step(const vpImage<unsigned char> &I, const vpMatrix &eJe, const vpColVector &) override
  {
    const Clock::time_point t0 = Clock::now();
    const TagView tag = detectTag(*m_tag, I);
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
class PbvsController : public Base
{
public:
  std::string name() const override { return "pbvs"; }
  Command step(const vpImage<unsigned char> &I, const vpMatrix &eJe, const vpColVector &) override
  {
    const Clock::time_point t0 = Clock::now();
    const TagView tag = detectTag(*m_tag, I);
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
    polygon that approximates it: the polygon's vertices move from one image to the next, and their moments kept the
    loop wandering a millimetre and a degree about the goal (seed 1's planar starts that converged: path ratios
    15-50, none within 1 mm and 0.5 deg).
  - "moments": ViSP's six features, xn, yn, an, c-invariants sx and sy, alpha, on the six degrees of freedom
    (EYEINHAND_L_cVe_eJe). On a thin object the c-invariants barely depend on the tilt (singular values of L down to
    0.003 on the pliers), and the pseudo-inverse commands metres per second from the first image.
  - "moments-planar": xn, yn, an and alpha on the camera's planar motions (vx, vy, vz, wz; EYEINHAND_CAMERA with
    the tilts disabled, then the estimated eMc, as "morph-vpservo"): the decoupled choice of Tahri and Chaumette for
    a camera parallel to the plane, which is what every set but 6dof starts from.
*/
class MomentsController : public Base
{
public:
  explicit MomentsController(bool planar = false) : m_planar(planar) {}
  std::string name() const override { return m_planar ? "moments-planar" : "moments"; }
  Command step(const vpImage<unsigned char> &I, const vpMatrix &eJe, const vpColVector &) override
  {
    const TagView tag = detectTag(*m_tag, I);
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
    leave the final errors within hundredths of a millimetre of the whole outline's (planar, planar-hard and noise
    sets, seed 1).
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

vpMorphBenchController::Command vpMorphBenchController::missingFrame()
{
  Command c;
  c.measured = false;
  return c;
}

std::vector<std::string> vpMorphBenchController::names()
{
  return {"morph",        "morph-planar", "morph-paper", "morph-vpservo", "ibvs-current",
          "ibvs-desired", "ibvs-mean",    "pbvs",        "moments",       "moments-planar"};
}

std::unique_ptr<vpMorphBenchController> vpMorphBenchController::create(const std::string &name)
{
  if (name == "morph")
    return std::unique_ptr<vpMorphBenchController>(new MorphController);
  if (name == "morph-planar")
    return std::unique_ptr<vpMorphBenchController>(new MorphController(MorphController::PLANAR));
  if (name == "morph-paper")
    return std::unique_ptr<vpMorphBenchController>(new MorphController(MorphController::PAPER));
  if (name == "morph-vpservo")
    return std::unique_ptr<vpMorphBenchController>(new MorphVpServoController);
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
  throw vpMorphException(vpMorphException::notFoundError,
                         "vpMorphBenchController: unknown controller '" + name +
                             "' (morph, morph-planar, morph-paper, morph-vpservo, ibvs-current, "
                             "ibvs-desired, ibvs-mean, pbvs, moments, moments-planar)");
}
