// The VISPMorph adapters of vpMorphBenchController: vpServoMorph ("morph", "morph-planar", "morph-paper") and
// vpFeatureMorph in a stock vpServo ("morph-vpservo").
#include "vpMorphBenchMorphAdapter.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include <visp3/core/vpExponentialMap.h>
#include <visp3/core/vpVelocityTwistMatrix.h>
#include <visp3/morph_vs/vpFeatureMorph.h>
#include <visp3/morph_vs/vpMorphJointVelocity.h>
#include <visp3/morph_vs/vpMorphServoGuard.h>
#include <visp3/morph_vs/vpMorphTiltEstimator.h>
#include <visp3/morph_vs/vpServoMorph.h>
#include <visp3/vs/vpServo.h>

namespace
{
// A status or verification name as one word of runs.csv ("tilt unbounded" -> "tilt-unbounded").
std::string dashed(std::string name)
{
  std::replace(name.begin(), name.end(), ' ', '-');
  return name;
}

/*!
  VISPMorph's controller: vpServoMorph through 10 sub-goals, Eq. 5-11, online hand-eye estimation, and the
  out-of-plane (tilt) correction on the final approach (vpServoMorph::TILT_FINAL_APPROACH: the contour's homography
  refined on the measured edge outlines, default dead zones), first turning the camera by kExplorationDeg about its
  optical axis and back to read the tilt of the camera on the hand (vpServoMorph::setHandEyeTiltExploration())
  ("morph"); or the planar law alone, no tilt command and no turn ("morph-planar"); or the paper's method as it is
  written (vpServoMorph::PAPER: elongation-vector rectification over the morph's correspondence, image-space rigid
  frames and deformation frames, the per-axis thresholds; no tilt, no turn: "morph-paper"). All give the servo the
  robot's joints (vpServoMorph::setJointState()), so that a half turn is planned the way that keeps them clear of their
  limits, and send the joint velocities that move the end-effector by the commanded twist over the period, solved on
  the arm's kinematic model (vpMorphJointVelocity): held for the period from the Jacobian at its start, a turn about
  the optical axis tilts the camera, a tilt the planar law does not take back.
*/
class MorphController : public vpMorphBenchMorphAdapter
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
    return toJoints(cmd, eJe, q);
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
  vpHomogeneousMatrix handEye() const override { return m_servo ? m_servo->get_eMc() : m_ctx.eMc; }
  void setTarget()
  {
    m_servo->setTarget(*m_template);
    if (m_ctx.recognizer)
      m_servo->getGuard().setTargetCheck(*m_ctx.recognizer, m_template->name(), kCheckSlack);
    else
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
      cmd.reason = dashed(vpServoMorph::statusName(s));
      break;
    }
    }
    if (s == vpServoMorph::CONVERGED || s == vpServoMorph::UNVERIFIED)
      cmd.verification = dashed(vpMorphServoGuard::verificationName(m_servo->getGuard().getVerification()));
    return cmd;
  }
  void reset() override
  {
    vpMorphBenchMorphAdapter::reset();
    m_servo.reset(new vpServoMorph);
    if (m_paper)
      m_servo->setMeasurement(vpServoMorph::PAPER);
    m_servo->setCameraParameters(m_ctx.cam);
    m_servo->set_eMc(m_ctx.eMc);
    m_servo->getPlanner().setSubGoalCount(10);
    m_servo->setSamplingTime(m_ctx.samplingTime);
    m_servo->setGain(lawShare());
    // Extracted contours are digitised: the final residual settles at a few tenths of a pixel.
    // The tilt's own final threshold stays the estimator's default, the same 0.002 rad.
    m_servo->setFinalThresholds(0.002, 0.2);
    // 0.05 % of the depth: a quarter millimetre at 0.5 m (the outlines' scale wanders by about 0.03 % under noise).
    m_servo->setFinalScaleThreshold(5e-4);
    if (m_tilt)
      m_servo->setTiltCorrection(vpServoMorph::TILT_FINAL_APPROACH);
    m_servo->getGuard().setMaxLostIterations(8); // its own stop before the loop's feature-lost (10)
    m_targetSet = false;
  }

  bool m_tilt, m_paper;
  std::string m_name;
  std::unique_ptr<vpServoMorph> m_servo;
  bool m_targetSet = false;
};

/*!
  vpFeatureMorph in a stock vpServo, to the final goal (no sub-goals): EYEINHAND_CAMERA with the tilt rotations
  disabled (setCameraDoF: the feature has 4 components for a planar task), current L. The two rotations the feature
  cannot see are vpMorphTiltEstimator's, as in vpServoMorph's final approach: its levelling twist, at the share of the
  displacement the planar law executes a period, is added to the task's camera velocity. The camera velocity is mapped
  to the end-effector with the estimated eMc and sent as joint velocities solved on the arm's model, as "morph" sends
  its own. The depth: the desired one times the scale the feature's last alignment measured (the area ratio to the
  template before the first). The target check runs on the first image and every kCheckPeriod measured iterations.
  Convergence: the adapter's stop rule on the error norm, the tilt levelled and verified
  (vpMorphTiltEstimator::isVerified() at vpMorphServoGuard's sigmas); settled with the tilt not verified is a safe stop
  ("unverified"), never a convergence.
*/
class MorphVpServoController : public vpMorphBenchMorphAdapter
{
public:
  std::string name() const override { return "morph-vpservo"; }
  Command step(const vpImage<unsigned char> &I, const vpMatrix &eJe, const vpColVector &q) override
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
        m_tilt.reset();
        m_tilt.setPixelSize(1.0 / std::max(m_ctx.cam.get_px(), m_ctx.cam.get_py()));
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
      vpColVector vc = m_task->computeControlLaw();
      // A view the feature's aligner does not explain gives a zero error: not a goal reached, a view not measured.
      if (!m_s.getAlignment().explained())
        return holdCommand(msSince(t0));
      const vpColVector e = m_task->getError();
      if (errorJumped(e))
        return stopCommand("feature-jump");
      // The tilt, between the features' own normalised contours: levelled at the planar law's rate.
      const double gain = lawShare();
      vpHomogeneousMatrix cMct;
      double Zp = 0.0;
      if (m_tilt.estimate(m_s.contour(), m_sd.contour(), Zd, al.transform, al.model == vpMorphViewAlignment::RIGID,
                          true, gain, cMct, Zp))
        vc += gain * vpExponentialMap::inverse(cMct, m_ctx.samplingTime);
      cmd.v = vpVelocityTwistMatrix(m_ctx.eMc) * vc;
      allowForHandEye(vc);
      // Stop rule: s - s* = (centroid, angle, log scale) as the outline's RMS displacement in pixels, and the tilt.
      const double r = radiusPx(c);
      const bool atGoal = settled(std::sqrt(e[0] * e[0] * m_ctx.cam.get_px() * m_ctx.cam.get_px() +
                                            e[1] * e[1] * m_ctx.cam.get_py() * m_ctx.cam.get_py() +
                                            r * r * (e[2] * e[2] + e[3] * e[3])),
                                  outlineNoisePx(c.outline().size()));
      const double sigmas = vpMorphServoGuard::getVerificationSigmas();
      if (atGoal && !m_tilt.isLevelling(sigmas)) {
        if (!m_tilt.isVerified(sigmas)) {
          Command stop = stopCommand("unverified");
          stop.verification = dashed(vpMorphServoGuard::verificationName(vpMorphServoGuard::TILT_UNBOUNDED));
          return stop;
        }
        cmd.converged = true;
        cmd.verification = dashed(vpMorphServoGuard::verificationName(vpMorphServoGuard::VERIFIED));
      }
    } catch (const vpException &e) {
      return stopCommand("feature-error");
    }
    cmd.controlMs = msSince(t0);
    if (!finite(cmd.v))
      return stopCommand("nan");
    return toJoints(cmd, eJe, q);
  }
  std::pair<const vpFeatureMorph *, const vpFeatureMorph *> features() const override { return {&m_s, &m_sd}; }

private:
  /*!
    A stock vpServo has no plan to re-make and no test of its own input: a view that jumps (a bump, the camera
    displaced, another shape taken for the object) would drag it anywhere. Its law makes each component of the error
    e = s - s* (centroid, angle, log scale) decrease by lambda dt of itself per period (L L+ = I for four features on
    four motions); a change of a component beyond twice that, plus 15 px, 2 deg or 5 % in scale (the bump the adapter
    detects), plus what the hand-eye error may add (allowForHandEye()), is a jump, and the adapter stops
    ("feature-jump") before sending the command. On the error, where the law's prediction holds, rather than on the
    fit's parameters, whose translation about the view's centroid moves with the rotation.
  */
  bool errorJumped(const vpColVector &e)
  {
    const double g = m_ctx.lambda * m_ctx.samplingTime;
    const double bump[4] = {15.0 / m_ctx.cam.get_px(), 15.0 / m_ctx.cam.get_py(), vpMath::rad(2.0), 0.05};
    bool jump = false;
    if (m_havePrev)
      for (unsigned int i = 0; i < 4 && !jump; ++i) {
        const double change = i == 2 ? std::remainder(e[i] - m_prevError[i], 2.0 * M_PI) : e[i] - m_prevError[i];
        jump = std::fabs(change + g * m_prevError[i]) > g * std::fabs(m_prevError[i]) + bump[i] + m_allowance[i];
      }
    m_prevError = e;
    m_havePrev = true;
    return jump;
  }
  /*!
    The law's prediction holds for the camera the twist \e vc was commanded to; the camera that moves differs from it
    by the hand-eye error, within the tolerance the context states (rotation phi, translation t). The executed twist
    is then V (v, w) with V the error's twist transform: its linear part differs from v by at most 2 sin(phi / 2) |v|
    + t |w|, its angular part from w by at most 2 sin(phi / 2) |w|. Through |L| (the feature's interaction, per
    component), this bounds how far the next change of each error component may stray from the prediction: zero for a
    calibrated arm, large while a wrong hand-eye turns a large rotation about the wrong point.
  */
  void allowForHandEye(const vpColVector &vc)
  {
    if (m_ctx.eMcRotationTolerance == 0.0 && m_ctx.eMcTranslationTolerance == 0.0)
      return; // a calibrated arm: the allowance stays 0, and no interaction matrix is computed on the control path
    const double chord = 2.0 * std::sin(0.5 * std::min(M_PI, m_ctx.eMcRotationTolerance));
    const double v = std::sqrt(vc[0] * vc[0] + vc[1] * vc[1] + vc[2] * vc[2]);
    const double w = std::sqrt(vc[3] * vc[3] + vc[4] * vc[4] + vc[5] * vc[5]);
    const double dv = chord * v + m_ctx.eMcTranslationTolerance * w, dw = chord * w;
    const vpMatrix L = m_s.interaction();
    for (unsigned int i = 0; i < 4; ++i) {
      double a = 0.0;
      for (unsigned int j = 0; j < 6; ++j)
        a += std::fabs(L[i][j]) * (j < 3 ? dv : dw);
      m_allowance[i] = std::isfinite(a) ? a * m_ctx.samplingTime : 0.0;
    }
  }
  void reset() override
  {
    vpMorphBenchMorphAdapter::reset();
    m_havePrev = false;
    std::fill(std::begin(m_allowance), std::end(m_allowance), 0.0);
    m_task.reset();
    m_s = vpFeatureMorph();
    m_sd = vpFeatureMorph();
    m_built = false;
    m_measured = 0;
    m_tilt.reset();
  }
  vpFeatureMorph m_s, m_sd;
  vpMorphTiltEstimator m_tilt;
  std::unique_ptr<vpServo> m_task;
  double m_areaD = 0;
  bool m_built = false;
  unsigned int m_measured = 0;
  bool m_havePrev = false;
  vpColVector m_prevError;              // the task's error at the last period
  double m_allowance[4] = {0, 0, 0, 0}; // what the hand-eye error may add to the next change (allowForHandEye())
};
} // namespace

std::unique_ptr<vpMorphBenchController> vpMorphBenchAdapter::createMorph(const std::string &name)
{
  if (name == "morph")
    return std::unique_ptr<vpMorphBenchController>(new MorphController);
  if (name == "morph-planar")
    return std::unique_ptr<vpMorphBenchController>(new MorphController(MorphController::PLANAR));
  if (name == "morph-paper")
    return std::unique_ptr<vpMorphBenchController>(new MorphController(MorphController::PAPER));
  if (name == "morph-vpservo")
    return std::unique_ptr<vpMorphBenchController>(new MorphVpServoController);
  return nullptr;
}
