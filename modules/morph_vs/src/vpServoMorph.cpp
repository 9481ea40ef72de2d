#include <visp3/morph_vs/vpServoMorph.h>

#include "vpMorphParameterCheck.h"

#include <cmath>
#include <sstream>

#include <visp3/core/vpExponentialMap.h>
#include <visp3/core/vpVelocityTwistMatrix.h>
#include <visp3/morph/vpMorphException.h>

namespace
{
// Image motion between two fits to one sub-goal that makes a hand-eye observation (rad, px): two hundred times the
// fits' noise (hundredths of a pixel), so that the regressors' noise does not shrink the estimated projection scale.
const double kObservationRotation = 0.05, kObservationPixels = 8.0;

bool allFinite(const vpColVector &v)
{
  for (unsigned int i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]))
      return false;
  return true;
}

double rmsRadius(const vpMorphContour &c)
{
  double cx, cy, s = 0;
  c.centroid(cx, cy);
  for (std::size_t k = 0; k < c.size(); ++k)
    s += (c.x(k) - cx) * (c.x(k) - cx) + (c.y(k) - cy) * (c.y(k) - cy);
  return std::sqrt(s / double(c.size()));
}
} // namespace

vpServoMorph::vpServoMorph()
  : m_cam(vpMorphViewAligner::getDefaultCameraParameters()), m_camIso(m_cam), m_ve(6, 0.0), m_vc(6, 0.0)
{
  m_task.setServo(vpServo::EYEINHAND_CAMERA);
  m_task.setInteractionMatrixType(vpServo::CURRENT);
  m_task.addFeature(m_s, m_sd);
  vpColVector dof(6, 1.0);
  dof[3] = dof[4] = 0.0; // planar task: no tilt
  m_task.setCameraDoF(dof);
  setCameraParameters(m_cam);
}

void vpServoMorph::setCameraParameters(const vpCameraParameters &cam)
{
  m_cam = cam;
  // The views are compared in square pixels (one focal length, the intrinsics' geometric mean): a similarity of the
  // object's plane is one of the image there whatever the intrinsics' aspect error, which only the law's conversion
  // to a motion sees (and the online calibration corrects).
  const double f = std::sqrt(cam.get_px() * cam.get_py());
  m_camIso = vpCameraParameters(f, f, cam.get_u0(), cam.get_v0());
  m_aligner.setCameraParameters(m_camIso);
  m_tilt.setPixelSize(1.0 / f);
  restart();
}

vpMorphRigidTransform vpServoMorph::toIntrinsics(const vpMorphRigidTransform &T) const
{
  const double f = m_camIso.get_px(), ax = f / m_cam.get_px(), ay = f / m_cam.get_py();
  return vpMorphRigidTransform(T.theta(), ax * T.tx(), ay * T.ty(), T.scale(), ax * T.cx(), ay * T.cy());
}

void vpServoMorph::setTarget(const vpMorphContour &target, double Zd)
{
  if (target.empty() || target.units() != vpMorphContour::PIXEL)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpServoMorph::setTarget: the target must be a non-empty contour in pixels");
  vpMorphParameterCheck::positive(Zd, "vpServoMorph", "the desired depth Zd");
  m_target.contour = target;
  m_target.depth = Zd;
  m_target.model = vpMorphTemplate();
  m_target.opening = 0.0;
  m_target.fixedPart = 0;
  restart();
}

void vpServoMorph::setTarget(const vpMorphTemplate &t)
{
  const double Zd = t.cdMo()[2][3];
  if (!(Zd > 0.0))
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpServoMorph::setTarget: the template has no desired pose (cdMo depth <= 0); set it "
                           "with vpMorphTemplate::setPlanarPose() or use setTarget(contour, Zd)");
  setTarget(t.contour(), Zd);
  if (t.isArticulated())
    m_target.model = t;
}

void vpServoMorph::setGain(double gain)
{
  vpMorphParameterCheck::positive(gain, "vpServoMorph", "the gain");
  if (gain > 1.0)
    throw vpMorphException(vpMorphException::badParameterError, "vpServoMorph::setGain: the gain must be <= 1");
  m_set.gain = gain;
}

void vpServoMorph::setSamplingTime(double dt)
{
  vpMorphParameterCheck::positive(dt, "vpServoMorph", "the sampling time");
  m_set.dt = dt;
}

void vpServoMorph::setControlLaw(ControlLaw law)
{
  m_set.law = law;
  restart();
}

void vpServoMorph::setTiltCorrection(TiltCorrection mode)
{
  m_set.tilt = mode;
  restart();
}

void vpServoMorph::setMeasurement(Measurement m)
{
  m_set.measurement = m;
  m_aligner.setMethod(m == PAPER ? vpMorphViewAligner::PAPER : vpMorphViewAligner::OUTLINE);
  m_planner.setRigidPath(m == PAPER ? vpMorphSubGoalPlanner::ABOUT_OBJECT_CENTROID
                                    : vpMorphSubGoalPlanner::CAMERA_STRAIGHT_LINE);
  m_planner.setDeformationFrames(m == PAPER);
  restart();
}

void vpServoMorph::setSubGoalThresholds(double rotationRad, double translationPx)
{
  vpMorphParameterCheck::positive(rotationRad, "vpServoMorph", "the sub-goal rotation threshold");
  vpMorphParameterCheck::positive(translationPx, "vpServoMorph", "the sub-goal translation threshold");
  m_set.thresholds.subRotation = rotationRad;
  m_set.thresholds.subPixels = translationPx;
}

void vpServoMorph::setFinalThresholds(double rotationRad, double translationPx)
{
  vpMorphParameterCheck::positive(rotationRad, "vpServoMorph", "the final rotation threshold");
  vpMorphParameterCheck::positive(translationPx, "vpServoMorph", "the final translation threshold");
  m_set.thresholds.finalRotation = rotationRad;
  m_set.thresholds.finalPixels = translationPx;
}

void vpServoMorph::setFinalScaleThreshold(double relativeScale)
{
  if (!(relativeScale >= 0.0 && relativeScale < 1.0))
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpServoMorph::setFinalScaleThreshold: the relative scale error must be in [0, 1)");
  m_set.thresholds.finalScale = relativeScale;
}

void vpServoMorph::setMinArea(double px2)
{
  vpMorphParameterCheck::positive(px2, "vpServoMorph", "the minimum area");
  m_set.minArea = px2;
}

void vpServoMorph::restart()
{
  m_started = m_havePrev = m_checked = false;
  m_guard.reset();
  m_planner.clear();
  m_tilt.reset();
  m_exploration.reset();
  m_k = 0;
  m_status = NOT_STARTED;
  m_iter = 0;
  m_current = vpMorphContour();
  m_alignment = vpMorphViewAlignment();
  m_res = Residuals();
  m_obs = Observation();
  m_history.clear();
  m_ve = vpColVector(6, 0.0);
  m_vc = vpColVector(6, 0.0);
  if (!m_target.contour.empty())
    m_aligner.setGoal(m_target.contour); // the exploration turn's goal, until the first plan
}

vpColVector vpServoMorph::stop(Status s)
{
  m_status = s;
  m_ve = vpColVector(6, 0.0);
  m_vc = vpColVector(6, 0.0);
  m_obs.anchored = false; // the robot does not move: nothing to observe
  record();
  return m_ve;
}

void vpServoMorph::setGoal(std::size_t k, const vpMorphRigidTransform *start)
{
  m_k = k;
  m_aligner.setGoal(m_planner.getSubGoal(k));
  if (start)
    m_aligner.setStart(*start);
  m_havePrev = false;
  m_obs.anchored = false;
}

bool vpServoMorph::plan(const vpMorphContour &current, bool replan, vpColVector &v)
{
  if (replan && !m_guard.allowReplan()) {
    v = stop(m_guard.getHaltedStatus());
    return false;
  }
  if (m_target.model.isArticulated())
    m_target.contour = m_target.model.viewFor(current, &m_target.opening, &m_target.fixedPart);
  if (m_guard.targetMismatch(current, m_target.contour, m_target.model.isArticulated())) {
    v = stop(m_guard.halt(TARGET_MISMATCH));
    return false;
  }
  // The view laid on the target from the correspondence, searched (any rotation, a part hidden or bent).
  m_aligner.setGoal(m_target.contour);
  const vpMorphViewAlignment a = m_aligner.align(current);
  if (!a.explained()) {
    m_started = false;
    v = stop(m_guard.hold(UNEXPLAINED_VIEW));
    return false;
  }
  m_planner.plan(current, m_target.contour, a.transform, m_camIso, m_target.depth, m_handEye.get_eMc(),
                 m_aligner.getTracker().correspondence());
  m_tilt.reset();
  // The plan's view is the current one: the map to each sub-goal is the fit to it now.
  const vpMorphRigidTransform start = m_planner.getPlannedMap(0);
  setGoal(0, &start);
  m_started = true;
  if (replan) {
    v = stop(REPLANNED);
    return false;
  }
  return true;
}

vpMorphRigidTransform vpServoMorph::toTarget(const vpMorphRigidTransform &T) const
{
  const std::size_t last = m_planner.size() - 1;
  if (m_k == last)
    return T;
  return m_planner.getPlannedMap(last) * m_planner.getPlannedMap(m_k).inverse() * T;
}

void vpServoMorph::residuals(const vpMorphViewAlignment &a, const vpMorphContour &current)
{
  const vpMorphRigidTransform &T = a.transform;
  m_res.rotation = std::fabs(T.theta());
  m_res.pixels = std::hypot(T.tx(), T.ty()) * m_camIso.get_px();
  m_res.scale = std::fabs(T.scale() - 1.0);
  m_res.radiusPx = rmsRadius(current);
  m_res.scalePixels = m_res.scale * m_res.radiusPx;
}

bool vpServoMorph::passed() const
{
  const vpMorphRigidTransform &T = m_alignment.transform;
  const bool translation = m_set.measurement == PAPER
                               ? std::fabs(T.tx() * m_camIso.get_px()) < m_set.thresholds.subPixels &&
                                     std::fabs(T.ty() * m_camIso.get_py()) < m_set.thresholds.subPixels
                               : m_res.pixels < m_set.thresholds.subPixels;
  return m_res.rotation < m_set.thresholds.subRotation && translation && m_res.scalePixels < m_set.thresholds.subPixels;
}

bool vpServoMorph::atGoal() const
{
  const vpMorphRigidTransform &T = m_alignment.transform;
  const bool translation = m_set.measurement == PAPER
                               ? std::fabs(T.tx() * m_camIso.get_px()) < m_set.thresholds.finalPixels &&
                                     std::fabs(T.ty() * m_camIso.get_py()) < m_set.thresholds.finalPixels
                               : m_res.pixels < m_set.thresholds.finalPixels;
  return m_k + 1 == m_planner.size() && m_res.rotation < m_set.thresholds.finalRotation && translation &&
         m_res.scalePixels < m_set.thresholds.finalPixels &&
         (m_set.thresholds.finalScale == 0.0 || m_res.scale < m_set.thresholds.finalScale);
}

void vpServoMorph::observe(const vpMorphRigidTransform &T)
{
  if (!m_set.online || !m_obs.anchored)
    return;
  m_obs.accumulated = m_obs.accumulated * m_obs.last;
  const vpMorphRigidTransform Tobs = T.inverse() * m_obs.T; // anchor view -> current view
  const double px = std::hypot(Tobs.tx(), Tobs.ty()) * m_camIso.get_px();
  if (std::fabs(Tobs.theta()) >= kObservationRotation || px >= kObservationPixels) {
    m_handEye.addMove(m_obs.accumulated, vpMorphSubGoalPlanner::cameraDisplacement(toIntrinsics(Tobs), m_obs.Z));
    m_obs.anchored = false; // re-anchored below
  }
}

vpColVector vpServoMorph::lawVelocity(const vpMorphRigidTransform &T, const vpMorphContour &currentN, double Z,
                                      double Zp)
{
  const vpHomogeneousMatrix eMc = m_handEye.get_eMc();
  const double k = m_handEye.translationScale();
  if (m_set.law == HOMOGENEOUS_TRANSFORMS) {
    const vpHomogeneousMatrix eMe =
        eMc * vpMorphSubGoalPlanner::cameraDisplacement(toIntrinsics(T), Zp, k) * eMc.inverse(); // Eq. 11
    return m_set.gain * vpExponentialMap::inverse(eMe, m_set.dt);
  }
  // A stock vpServo over vpFeatureMorph, to the current sub-goal: it measures its own error (vpFeatureMorph::error()).
  m_sd.buildFrom(m_planner.getSubGoal(m_k), m_camIso, m_planner.getDepth(m_k));
  m_s.buildFrom(currentN, Z);
  m_task.setLambda(m_set.gain / m_set.dt);
  vpColVector vc = m_task.computeControlLaw();
  vc[0] *= k;
  vc[1] *= k;
  return vpVelocityTwistMatrix(eMc) * vc;
}

void vpServoMorph::record()
{
  Iteration it;
  it.iteration = m_iter;
  it.subGoal = m_k;
  it.status = m_status;
  it.rotationResidual = m_res.rotation;
  it.translationResidual = m_res.pixels;
  it.scaleResidual = m_res.scalePixels;
  it.model = m_alignment.model;
  it.eMc = m_handEye.get_eMc();
  it.translationScale = m_handEye.translationScale();
  it.ve = m_ve;
  it.tiltResidual = m_tilt.getResidual();
  m_history.push_back(it);
}

vpColVector vpServoMorph::computeControlLaw(const vpMorphContour &current)
{
  if (m_target.contour.empty())
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpServoMorph::computeControlLaw: no target; call setTarget() first");
  if (!current.empty() && current.units() != vpMorphContour::PIXEL)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpServoMorph::computeControlLaw: the current contour must be in pixels");
  ++m_iter;
  m_current = current;
  if (m_guard.isHalted())
    return stop(m_guard.getHaltedStatus());
  if (current.empty()) // hold: the plan and the last fit are kept
    return stop(m_guard.hold(TARGET_LOST));
  const double area = current.area();
  if (!std::isfinite(area) || area < m_set.minArea)
    return stop(m_guard.hold(DEGENERATE_CONTOUR));
  try {
    const vpMorphContour currentN = current.toNormalized(m_camIso);
    vpColVector v;
    // The target checked on the task's first view, before anything moves (the exploration turn, then the plan).
    if (!m_checked) {
      m_checked = true;
      if (m_guard.targetMismatch(current, m_target.contour, m_target.model.isArticulated()))
        return stop(m_guard.halt(TARGET_MISMATCH));
      if (m_target.model.isArticulated()) { // posed at the opening the view shows, the exploration's goal too
        m_target.contour = m_target.model.viewFor(current, &m_target.opening, &m_target.fixedPart);
        m_aligner.setGoal(m_target.contour);
      }
    }
    if (m_exploration.isActive()) {
      // The exploration turn before the first plan: the view laid on the target reads its tilt.
      // A view the target does not explain (another region joined to the object at the image's border) is not read,
      // and the turn goes on by its own rules. The view turned by the last command since the last one.
      m_aligner.turnStart(m_exploration.getLastTurn());
      const vpMorphViewAlignment a = m_aligner.align(current);
      const vpMorphSubGoalPlanner &p = m_planner;
      const vpMorphHandEyeExploration::Result r = m_exploration.step(
          current, currentN, m_aligner.getGoalNormalized(), m_target.depth, a.explained() ? &a.transform : nullptr,
          m_camIso, m_tilt, m_handEye, p.getJointJacobian(), p.getJointPositions(), p.getJointMin(), p.getJointMax(),
          m_set.dt, m_guard.getJumpPixels(), v);
      if (r == vpMorphHandEyeExploration::TURNING) {
        m_status = MOVING;
        m_ve = v;
        m_vc = vpVelocityTwistMatrix(m_handEye.get_eMc().inverse()) * v;
        record();
        return m_ve;
      }
      m_started = false;
      if (r == vpMorphHandEyeExploration::DISPLACED && !plan(current, true, v))
        return v;
    }
    if (!m_started && !plan(current, false, v))
      return v;

    // From the last fit moved by the share of it the last command executed (the view moved a step towards its goal).
    if (m_havePrev)
      m_aligner.setStart(m_prevT.interpolated(1.0 - m_set.gain), m_alignment.sigmaPx);
    m_alignment = m_aligner.align(current);
    if (!m_alignment.explained()) {
      m_havePrev = false;
      return stop(m_guard.hold(UNEXPLAINED_VIEW));
    }
    m_guard.resume();
    if (m_havePrev && m_guard.viewJumped(m_alignment.transform, m_prevT, m_set.gain, m_camIso)) {
      // The view jumped (the robot or the object was displaced): a new plan from it, bounded.
      plan(current, true, v);
      return v;
    }
    residuals(m_alignment, current);
    observe(m_alignment.transform);
    m_status = MOVING;
    while (m_k + 1 < m_planner.size() && passed()) {
      const vpMorphRigidTransform start = m_planner.getStep(m_k) * m_alignment.transform;
      setGoal(m_k + 1, &start);
      m_alignment = m_aligner.align(current);
      if (!m_alignment.explained())
        return stop(m_guard.hold(UNEXPLAINED_VIEW));
      residuals(m_alignment, current);
      m_status = SUBGOAL_REACHED;
    }
    const vpMorphRigidTransform &T = m_alignment.transform;
    const double Z = m_planner.getDepth(m_k) * T.scale(); // the view is s times smaller than the sub-goal's
    // Out-of-plane part (identity when off or not estimated).
    const bool last = m_k + 1 == m_planner.size();
    const bool tiltOn =
        m_set.measurement == OUTLINE && (m_set.tilt == TILT_ALWAYS || (m_set.tilt == TILT_FINAL_APPROACH && last));
    vpHomogeneousMatrix cMct;
    double Zp = Z;
    const bool tilt =
        tiltOn && m_tilt.estimate(currentN, m_target.contour.toNormalized(m_camIso), m_target.depth, toTarget(T),
                                  m_alignment.model == vpMorphViewAlignment::RIGID, last, m_set.gain, cMct, Zp);
    // At the goal in the plane: stop, unless a tilt is seen and still being levelled (no estimate: the tilt is unknown,
    // and the verification says so).
    const double sigmas = vpMorphServoGuard::getVerificationSigmas();
    if (atGoal() && !(tiltOn && m_tilt.isLevelling(sigmas))) {
      if (m_guard.targetMismatch(current, m_target.contour,
                                 m_target.model.isArticulated())) // never CONVERGED on another shape
        return stop(m_guard.halt(TARGET_MISMATCH));
      // Verified by the guard (never the paper's measurement, which carries no covariance and sees no tilt).
      const Status s = m_guard.verify(m_alignment, m_set.thresholds.finalRotation, m_set.thresholds.finalPixels,
                                      m_set.thresholds.finalPixels, m_res.radiusPx, m_camIso.get_px(),
                                      !tiltOn || m_tilt.isVerified(sigmas));
      return stop(m_guard.halt(s));
    }

    const vpColVector vePlanar = lawVelocity(T, currentN, Z, tilt ? Zp : Z);
    vpColVector ve = vePlanar;
    if (tilt)
      ve += m_set.gain * (vpVelocityTwistMatrix(m_handEye.get_eMc()) * vpExponentialMap::inverse(cMct, m_set.dt));
    if (!allFinite(ve))
      return stop(m_guard.hold(DEGENERATE_CONTOUR));
    m_ve = ve;
    m_vc = vpVelocityTwistMatrix(m_handEye.get_eMc().inverse()) * ve;
    // The hand-eye observation: the planar move commanded since an anchor (a fit to this sub-goal) against the image
    // motion; none spans a tilt command, which the planar model would misread.
    m_obs.last = vpExponentialMap::direct(vePlanar, m_set.dt);
    if (!m_obs.anchored) {
      m_obs.T = T;
      m_obs.Z = Z;
      m_obs.accumulated.eye();
      m_obs.anchored = true;
    }
    if (tilt && m_tilt.commanded())
      m_obs.anchored = false;
    m_prevT = T;
    m_havePrev = true;
    record();
    return m_ve;
  } catch (const vpException &) {
    // A contour the morph cannot use: hold rather than throw from inside a control loop.
    return stop(m_guard.hold(DEGENERATE_CONTOUR));
  }
}
