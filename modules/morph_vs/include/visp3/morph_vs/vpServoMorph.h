/*!
  \file vpServoMorph.h
  \brief The morph-goal servo task: servo through the virtual contours of a morph, with online hand-eye estimation.
*/
#ifndef VP_SERVO_MORPH_H
#define VP_SERVO_MORPH_H

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpColor.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpRGBa.h>
#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphRigidTransform.h>
#include <visp3/morph/vpMorphTemplate.h>
#include <visp3/morph_vs/vpFeatureMorph.h>
#include <visp3/morph_vs/vpMorphHandEyeEstimator.h>
#include <visp3/morph_vs/vpMorphHandEyeExploration.h>
#include <visp3/morph_vs/vpMorphServoGuard.h>
#include <visp3/morph_vs/vpMorphServoStatus.h>
#include <visp3/morph_vs/vpMorphSubGoalPlanner.h>
#include <visp3/morph_vs/vpMorphTiltEstimator.h>
#include <visp3/morph_vs/vpMorphViewAligner.h>
#include <visp3/vs/vpServo.h>

/*!
  \class vpServoMorph
  \ingroup group_morph_vs
  \brief The paper's controller: the contours of the morph from the current view to the target are the successive
  goals (sub-goals) of an eye-in-hand robot, and the hand-eye transform is estimated on line.

  A thin front over its parts, each reached through an accessor:
  - getAligner() (vpMorphViewAligner): the one measurement, the similarity from the current view to the current
    sub-goal and how well it explains the view;
  - getPlanner() (vpMorphSubGoalPlanner): the sub-goals, their camera path, the joints;
  - getTiltEstimator() (vpMorphTiltEstimator): the out-of-plane correction (setTiltCorrection());
  - getHandEyeEstimator() and getHandEyeExploration(): the online hand-eye estimate and its exploration turn;
  - getGuard() (vpMorphServoGuard): holds, stops, re-plans, the target check, the verification of CONVERGED.

  <b>Each period</b> (computeControlLaw(), once per sampling period after the robot executed the last velocity): the
  view is aligned on the current sub-goal; a sub-goal within getSubGoalRotationThreshold() and
  getSubGoalTranslationThreshold() (the paper's 0.10 rad and 5 px) is passed; through the projection of a plane
  parallel to the image at the current depth Z (the sub-goal's depth times the alignment's scale) the similarity
  (theta, t, s about the current centroid c, normalised coordinates) is the camera displacement
  \f${}^cM_{c'} = [R_z(-\theta),\ (k Z (c - R(-\theta)(c + t)/s),\ Z (1 - 1/s))]\f$ (k: the estimated projection
  scale), and Eq. 11 makes it an end-effector one, \f${}^eM_{e'} = {}^eM_c\, {}^cM_{c'}\, {}^eM_c^{-1}\f$; the output
  is the velocity of a share getGain() of it over the sampling time, \f$v_e = \mathrm{gain} \cdot \log({}^eM_{e'}) /
  \Delta t\f$ (STOCK_VPSERVO: a stock vpServo over vpFeatureMorph instead). The image motion observed between two fits
  to the same sub-goal, against the moves commanded, updates the hand-eye estimate once it exceeds 8 px or 0.05 rad.
  At the target within the final thresholds, the guard verifies the alignment (CONVERGED or UNVERIFIED).

  <b>Measurement</b> (setMeasurement()): OUTLINE, the project's (vpMorphViewAligner::OUTLINE: the robust outline fit,
  hidden and bent parts left out, the rigid frames on the straight camera path and no deformation frames), or PAPER,
  the paper's (elongation vectors over the correspondence, image-space rigid frames then the deformation frames of
  Eq. 1, the paper's thresholds per axis, no tilt). The paper's thresholds stop it, UNVERIFIED: its measurement
  carries no uncertainty and sees no tilt, so it cannot vouch for the pose (vpMorphServoGuard::verify()).

  Not copyable (it owns a vpServo that points to its own features).

  \code
  vpServoMorph servo;
  servo.setCameraParameters(cam);
  servo.set_eMc(eMc);
  servo.setTarget(db["pliers"]);                 // a template with its desired pose
  servo.getPlanner().setSubGoalCount(10);
  vpColVector ve = servo.computeControlLaw(vpMorphContourExtractor().extract(I));
  if (servo.getStatus() == vpServoMorph::CONVERGED) { }
  \endcode
  \sa vpMorphViewAligner, vpMorphServoGuard, vpMorphServoStatus
*/
class vpServoMorph : public vpMorphServoStatus
{
public:
  //! How the sub-goal error becomes a velocity.
  enum ControlLaw {
    HOMOGENEOUS_TRANSFORMS, //!< The paper's Eq. 5-11 (default).
    STOCK_VPSERVO           //!< A stock vpServo over vpFeatureMorph.
  };
  //! When the out-of-plane correction runs.
  enum TiltCorrection {
    TILT_OFF,            //!< The paper's planar law (default).
    TILT_FINAL_APPROACH, //!< On the last sub-goal (the target).
    TILT_ALWAYS          //!< From the first period.
  };
  //! Which measurement the servo runs on.
  enum Measurement {
    OUTLINE, //!< The project's (default).
    PAPER    //!< The paper's.
  };
  //! One period, for plots.
  struct Iteration
  {
    //! period number from the restart
    unsigned int iteration = 0;
    //! sub-goal chased
    std::size_t subGoal = 0;
    //! status after the period
    Status status = NOT_STARTED;
    double rotationResidual = 0;                                           //!< |theta| to the sub-goal (rad)
    double translationResidual = 0;                                        //!< |t| to the sub-goal (px)
    double scaleResidual = 0;                                              //!< |s - 1| times the view's RMS radius (px)
    vpMorphViewAlignment::Model model = vpMorphViewAlignment::UNEXPLAINED; //!< the aligner's model of the view
    vpHomogeneousMatrix eMc;                                               //!< hand-eye estimate after this period
    double translationScale = 1; //!< projection scale estimate after this period
    vpColVector ve;              //!< commanded end-effector velocity
    double tiltResidual = 0;     //!< estimated tilt (rad), 0 if not estimated
  };

  vpServoMorph();
  vpServoMorph(const vpServoMorph &) = delete;
  vpServoMorph &operator=(const vpServoMorph &) = delete;

  /*!
    Intrinsics (an estimate: they may be off). Restarts. The views are compared in square pixels (focal length
    sqrt(px py)): square pixels make a similarity of the object's plane one of the image, whatever error the estimated
    aspect ratio has; the intrinsics turn the measured similarity into a camera motion.
  */
  void setCameraParameters(const vpCameraParameters &cam);
  //! The intrinsics the servo uses.
  const vpCameraParameters &getCameraParameters() const { return m_cam; }
  //! Initial hand-eye estimate; restarts the estimator.
  void set_eMc(const vpHomogeneousMatrix &eMc) { m_handEye.reset(eMc); }
  //! The current hand-eye estimate.
  vpHomogeneousMatrix get_eMc() const { return m_handEye.get_eMc(); }
  //! Whether the hand-eye estimate is updated on line (default true).
  void setOnlineCalibration(bool on) { m_set.online = on; }
  //! Whether the hand-eye estimate is updated on line.
  bool getOnlineCalibration() const { return m_set.online; }

  /*!
    The goal: the target contour in pixels, seen from the desired pose at depth Zd (object plane parallel to the
    image). Restarts.
    \throw vpMorphException::badParameterError on an empty contour or one not in pixels, or Zd not finite and > 0.
  */
  void setTarget(const vpMorphContour &target, double Zd);
  /*!
    The goal from a template (its contour and the depth of its cdMo). An articulated template is posed, at each plan,
    at the opening its current view shows (vpMorphTemplate::viewFor()).
    \throw vpMorphException::badParameterError when the template has no desired pose.
  */
  void setTarget(const vpMorphTemplate &t);
  //! The target contour (pixels), as set or posed at its opening.
  const vpMorphContour &getTargetContour() const { return m_target.contour; }
  //! The target's depth Zd (m).
  double getTargetDepth() const { return m_target.depth; }
  //! The opening the articulated target was posed at (radians; 0 for a rigid target).
  double getTargetOpening() const { return m_target.opening; }
  //! The part of the articulated target that stays where the taught view has it (0 or 1).
  unsigned int getTargetFixedPart() const { return m_target.fixedPart; }

  //! Share of the step commanded per sampling period, in (0, 1] (default 0.5).
  void setGain(double gain);
  //! Share of the step commanded per period.
  double getGain() const { return m_set.gain; }
  //! Sampling period (s, > 0, default 0.1).
  void setSamplingTime(double dt);
  //! Sampling period (s).
  double getSamplingTime() const { return m_set.dt; }
  //! How the error becomes a velocity (default HOMOGENEOUS_TRANSFORMS).
  void setControlLaw(ControlLaw law);
  //! How the error becomes a velocity.
  ControlLaw getControlLaw() const { return m_set.law; }
  //! Restarts.
  void setTiltCorrection(TiltCorrection mode);
  //! When the out-of-plane correction runs.
  TiltCorrection getTiltCorrection() const { return m_set.tilt; }
  //! Restarts; PAPER also sets the planner's path and deformation frames and the aligner's method, OUTLINE resets them.
  void setMeasurement(Measurement m);
  //! Which measurement the servo runs on.
  Measurement getMeasurement() const { return m_set.measurement; }
  //! Residual below which a sub-goal is passed (default: the paper's 0.10 rad and 5 px).
  void setSubGoalThresholds(double rotationRad, double translationPx);
  //! Rotation residual below which a sub-goal is passed (rad).
  double getSubGoalRotationThreshold() const { return m_set.thresholds.subRotation; }
  //! Translation residual below which a sub-goal is passed (px).
  double getSubGoalTranslationThreshold() const { return m_set.thresholds.subPixels; }
  //! Residual below which the target is reached (default 0.001 rad and 0.1 px, the scale's error counted in pixels
  //! at the view's RMS radius).
  void setFinalThresholds(double rotationRad, double translationPx);
  //! Rotation residual below which the target is reached (rad).
  double getFinalRotationThreshold() const { return m_set.thresholds.finalRotation; }
  //! Translation residual below which the target is reached (px).
  double getFinalTranslationThreshold() const { return m_set.thresholds.finalPixels; }
  //! Relative scale error below which the target is reached, on top (default 0: none).
  void setFinalScaleThreshold(double relativeScale);
  //! Relative scale error below which the target is reached (0: none).
  double getFinalScaleThreshold() const { return m_set.thresholds.finalScale; }
  //! Smallest contour area (px^2, > 0, default 25): below, DEGENERATE_CONTOUR.
  void setMinArea(double px2);
  //! Smallest contour area (px^2).
  double getMinArea() const { return m_set.minArea; }

  //! The measurement (vpMorphViewAligner).
  vpMorphViewAligner &getAligner() { return m_aligner; }
  //! The measurement (vpMorphViewAligner).
  const vpMorphViewAligner &getAligner() const { return m_aligner; }
  //! Its settings take effect at the next plan (restart()); setJointState() every period.
  vpMorphSubGoalPlanner &getPlanner() { return m_planner; }
  //! The sub-goal planner.
  const vpMorphSubGoalPlanner &getPlanner() const { return m_planner; }
  //! The out-of-plane (tilt) estimator.
  vpMorphTiltEstimator &getTiltEstimator() { return m_tilt; }
  //! The out-of-plane (tilt) estimator.
  const vpMorphTiltEstimator &getTiltEstimator() const { return m_tilt; }
  //! The online hand-eye estimator.
  vpMorphHandEyeEstimator &getHandEyeEstimator() { return m_handEye; }
  //! The online hand-eye estimator.
  const vpMorphHandEyeEstimator &getHandEyeEstimator() const { return m_handEye; }
  //! The hand-eye tilt exploration turn.
  vpMorphHandEyeExploration &getHandEyeExploration() { return m_exploration; }
  //! The hand-eye tilt exploration turn.
  const vpMorphHandEyeExploration &getHandEyeExploration() const { return m_exploration; }
  //! The guard: holds, stops, re-plans, the target check.
  vpMorphServoGuard &getGuard() { return m_guard; }
  //! The guard: holds, stops, re-plans, the target check.
  const vpMorphServoGuard &getGuard() const { return m_guard; }

  //! Forgets the plan, the history and the stops: the next period plans from the then current view.
  void restart();
  /*!
    One period: the end-effector velocity (6, ViSP order v, w) to apply for getSamplingTime(); zero with a hold or a
    stop (getStatus()). An empty contour: nothing seen (a hold).
    \throw vpMorphException::badParameterError without a target or for a contour not in pixels.
  */
  vpColVector computeControlLaw(const vpMorphContour &current);

  //! The status after the last period.
  Status getStatus() const { return m_status; }
  //! Index of the sub-goal chased (the last one is the target).
  std::size_t getSubGoalIndex() const { return m_k; }
  //! The sub-goals of the current plan (pixels).
  const std::vector<vpMorphContour> &getSubGoals() const { return m_planner.getSubGoals(); }
  //! The last alignment to the current sub-goal.
  const vpMorphViewAlignment &getAlignment() const { return m_alignment; }
  //! |theta| from the view to the sub-goal (rad).
  double getRotationResidual() const { return m_res.rotation; }
  //! |t| from the view to the sub-goal (px).
  double getTranslationResidual() const { return m_res.pixels; }
  //! |s - 1| times the view's RMS radius (px).
  double getScaleResidual() const { return m_res.scalePixels; }
  //! The last contour given (pixels; empty after a hold without one).
  const vpMorphContour &getCurrentContour() const { return m_current; }
  //! The last velocity commanded (end-effector frame, v then w).
  const vpColVector &getEndEffectorVelocity() const { return m_ve; }
  //! The last velocity in the estimated camera frame.
  const vpColVector &getCameraVelocity() const { return m_vc; }
  //! One entry per period since the last restart.
  const std::vector<Iteration> &getHistory() const { return m_history; }

  /*!
    Draws in one call what the servo sees and chases, on the display attached to \e I (vpDisplay: no-op without one):
    - the target (\e targetColor, \e thickness + 2 pixels wide, underneath the rest, so that it stays visible where
      the current contour reaches it);
    - the current sub-goal while it is not the target (\e subGoalColor);
    - the alignment from the current contour to that sub-goal, a line from every few vertices to where the measured
      similarity lays it (cyan), while the servo moves or has converged;
    - the last contour given to computeControlLaw() (\e currentColor);
    - the status in yellow on a black band in the top-left corner: statusName(), the sub-goal chased (k / n), the
      residuals to it (rad, px; none during the exploration turn), the view's model and the tilt when it is
      estimated.
    \code
    vpImage<unsigned char> I;                // the camera image
    vpDisplayX d(I, 0, 0, "camera");         // or vpDisplayOpenCV
    for (;;) {
      acquire(I);                            // the user's grabber
      const vpColVector ve = servo.computeControlLaw(vpMorphContourExtractor().extract(I));
      vpDisplay::display(I);
      servo.display(I);
      vpDisplay::flush(I);
      if (vpServoMorph::isStop(servo.getStatus())) break;
      robot.setVelocity(vpRobot::END_EFFECTOR_FRAME, ve);
    }
    \endcode
  */
  void display(const vpImage<unsigned char> &I, const vpColor &currentColor = vpColor::red,
               const vpColor &subGoalColor = vpColor::orange, const vpColor &targetColor = vpColor::green,
               unsigned int thickness = 1) const;
  //! Same on a colour image's display.
  void display(const vpImage<vpRGBa> &I, const vpColor &currentColor = vpColor::red,
               const vpColor &subGoalColor = vpColor::orange, const vpColor &targetColor = vpColor::green,
               unsigned int thickness = 1) const;
  //! What display() draws, burnt into the pixels of \e I (vpImageDraw, vpFont): video frames without a window.
  void draw(vpImage<vpRGBa> &I, const vpColor &currentColor = vpColor::red,
            const vpColor &subGoalColor = vpColor::orange, const vpColor &targetColor = vpColor::green,
            unsigned int thickness = 1) const;
  //! The status lines display() writes.
  std::vector<std::string> statusText() const;
  //! The lines display() draws for the alignment: a few vertices of the current contour and where it lays them (px).
  std::vector<std::pair<vpImagePoint, vpImagePoint>> alignmentLines() const;

private:
  struct Thresholds
  {
    double subRotation = 0.10, subPixels = 5.0, finalRotation = 0.001, finalPixels = 0.1, finalScale = 0.0;
  };
  struct Residuals
  {
    double rotation = 0.0, pixels = 0.0, scale = 0.0, scalePixels = 0.0, radiusPx = 0.0;
  };
  // The target: its contour, its template (none for a rigid target), its depth, and the opening and fixed part an
  // articulated one was posed at.
  struct TargetState
  {
    vpMorphContour contour;
    vpMorphTemplate model;
    double depth = 0.5, opening = 0.0;
    unsigned int fixedPart = 0;
  };
  // The user's settings of the law.
  struct Settings
  {
    double gain = 0.5, dt = 0.1, minArea = 25.0;
    ControlLaw law = HOMOGENEOUS_TRANSFORMS;
    TiltCorrection tilt = TILT_OFF;
    Measurement measurement = OUTLINE;
    bool online = true;
    Thresholds thresholds;
  };
  // The hand-eye observation between fits to one sub-goal: the fit and depth at the anchor, the moves since.
  struct Observation
  {
    bool anchored = false;
    vpMorphRigidTransform T;
    double Z = 0.0;
    vpHomogeneousMatrix accumulated, last;
  };

  bool plan(const vpMorphContour &current, bool replan, vpColVector &v);
  vpColVector stop(Status s);
  void setGoal(std::size_t k, const vpMorphRigidTransform *start);
  vpMorphRigidTransform toTarget(const vpMorphRigidTransform &T) const;
  //! A similarity measured in the square-pixel camera, its centre and translation in the intrinsics' coordinates.
  vpMorphRigidTransform toIntrinsics(const vpMorphRigidTransform &T) const;
  void residuals(const vpMorphViewAlignment &a, const vpMorphContour &current);
  bool passed() const;
  bool atGoal() const;
  void observe(const vpMorphRigidTransform &T);
  vpColVector lawVelocity(const vpMorphRigidTransform &T, const vpMorphContour &currentN, double Z, double Zp);
  void record();

  vpCameraParameters m_cam, m_camIso; // the intrinsics, and the square-pixel camera the views are compared in
  TargetState m_target;
  Settings m_set;
  vpMorphContour m_current;

  vpMorphViewAligner m_aligner;
  vpMorphSubGoalPlanner m_planner;
  vpMorphTiltEstimator m_tilt;
  vpMorphHandEyeEstimator m_handEye;
  vpMorphHandEyeExploration m_exploration;
  vpMorphServoGuard m_guard;

  bool m_started = false, m_havePrev = false, m_checked = false; // m_checked: the first view's target check
  std::size_t m_k = 0;
  Status m_status = NOT_STARTED;
  unsigned int m_iter = 0;
  vpMorphViewAlignment m_alignment;
  vpMorphRigidTransform m_prevT; // the last period's fit to the same sub-goal
  Residuals m_res;
  Observation m_obs;
  vpColVector m_ve, m_vc;
  std::vector<Iteration> m_history;
  vpFeatureMorph m_s, m_sd; // STOCK_VPSERVO
  vpServo m_task;
};

#endif
