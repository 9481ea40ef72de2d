/*!
  \file vpMorphServoGuard.h
  \brief What keeps the morph servo safe: holds, stops, view jumps, the target check and the verification of its
  convergence.
*/
#ifndef VP_MORPH_SERVO_GUARD_H
#define VP_MORPH_SERVO_GUARD_H

#include <cstddef>
#include <limits>
#include <memory>
#include <string>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphDatabase.h>
#include <visp3/morph/vpMorphPartRecognizer.h>
#include <visp3/morph/vpMorphRigidTransform.h>
#include <visp3/morph_vs/vpMorphServoStatus.h>
#include <visp3/morph_vs/vpMorphViewAlignment.h>

/*!
  \class vpMorphServoGuard
  \ingroup group_morph_vs
  \brief The part of vpServoMorph that decides its statuses (vpMorphServoStatus): a hold, a stop, a re-plan, a
  converged goal or one it cannot vouch for.

  - <b>Holds.</b> A period without a usable view (no contour, a degenerate one, one its goal does not explain) is a
    hold (zero velocity); more than getMaxLostIterations() in a row stop the servo (LOST_TOO_LONG).
  - <b>Jumps.</b> The fit to the same goal moves, from one period to the next, by the fraction of its residual the
    last command executed; beyond that in rotation (by getJumpRotation()) or translation (by getJumpPixels()), the
    view jumped (the robot or the object was displaced): re-plan, at most getMaxReplans() times (TOO_MANY_REPLANS).
  - <b>Target check</b> (setTargetCheck()): the view is not the target when the database does not accept it as the
    target's template (vpMorphDatabase::accepts(), with a slack: an occluded view of the target is the target), or
    when the database's best template is another one, accepted, that costs getMismatchRatio() times less work and
    explains more of the view's outline (vpMorphDatabase::support()). Given a vpMorphPartRecognizer, its RIGID stage
    decides first where it names the view's part.
  - <b>Verification</b> (verify()): at the target, the measurement says aligned; CONVERGED only if the aligned view
    explains the target (vpMorphViewAlignment::explained()) within the final thresholds and pins the pose: three
    standard deviations of the alignment's rotation, translation and scale (vpMorphViewAlignment::covariance) within
    the final thresholds, and, when it is corrected, the tilt's estimate plus as many of its deviations within its own
    final threshold (vpMorphTiltEstimator::isVerified()). A view explained only in part (a part hidden or bent) needs
    the target check too: another shape may share more than half of the target's outline. Otherwise UNVERIFIED, a
    stop: a servo that cannot tell where it stands says so instead of claiming the goal; getVerification() says
    which test failed.

  \code
  vpMorphServoGuard &guard = servo.getGuard();
  guard.setMaxLostIterations(8);
  guard.setTargetCheck(db, "pliers");
  \endcode
  \sa vpServoMorph, \ref page_servo_measurement
*/
class vpMorphServoGuard : public vpMorphServoStatus
{
public:
  //! Default limits, no target check.
  vpMorphServoGuard() = default;

  //! Holds in a row allowed before LOST_TOO_LONG (default 25).
  void setMaxLostIterations(unsigned int n) { m_maxLost = n; }
  //! Holds in a row allowed.
  unsigned int getMaxLostIterations() const { return m_maxLost; }
  //! Re-plans allowed per task (default 3; 0: the first jump stops).
  void setMaxReplans(unsigned int n) { m_maxReplans = n; }
  //! Re-plans allowed per task.
  unsigned int getMaxReplans() const { return m_maxReplans; }
  //! Translation of the fit beyond what the last command explains that is a jump (pixels, > 0, default 20).
  void setJumpPixels(double px);
  //! The translation jump threshold (px).
  double getJumpPixels() const { return m_jumpPx; }
  //! Rotation of the fit beyond what the last command explains that is a jump (rad, > 0, default 0.1).
  void setJumpRotation(double rad);
  //! The rotation jump threshold (rad).
  double getJumpRotation() const { return m_jumpRotation; }
  /*!
    Checks the view against \e db's template \e name, with the factor \e slack (>= 1) on its acceptance threshold.
    \throw vpMorphException::notFoundError for an unknown name, badParameterError for a slack below 1 or NaN.
  */
  void setTargetCheck(const vpMorphDatabase &db, const std::string &name, double slack = getDefaultSlack());
  /*!
    As setTargetCheck(db, name, slack) over the recognizer's database, where the recognizer's RIGID stage decides
    first (vpMorphPartRecognizer::namedAs()): a view it names as the target's part is the target, one it names as
    another's is not; the database's rules judge the rest. The check then agrees with the recognition that chose the
    target (an occluded view named by the rigid check may show less of its outline than the distance's support asks).
  */
  void setTargetCheck(const vpMorphPartRecognizer &recognizer, const std::string &name,
                      double slack = getDefaultSlack());
  //! The target check's default slack on the acceptance threshold.
  static double getDefaultSlack() { return 1.25; }
  //! No target check from now on.
  void clearTargetCheck();
  //! True when a target check is set.
  bool hasTargetCheck() const { return m_db != nullptr; }
  //! The database of the target check (empty without).
  const vpMorphDatabase &getTargetDatabase() const;
  //! Another template replaces the target when it costs this much less work (1.2).
  static double getMismatchRatio() { return 1.2; }

  //! A new task: counts and stops forgotten (the settings kept).
  void reset();
  //! The stop the servo is in (NOT_STARTED when it is not stopped).
  bool isHalted() const { return m_halted != NOT_STARTED; }
  //! The stop latched (NOT_STARTED when none).
  Status getHaltedStatus() const { return m_halted; }
  //! Latches the stop \e s and returns it.
  Status halt(Status s);
  //! A period without a usable view (\e why: TARGET_LOST, DEGENERATE_CONTOUR or UNEXPLAINED_VIEW): \e why, or
  //! LOST_TOO_LONG (halted) beyond the limit.
  Status hold(Status why);
  //! A period with a usable view: the holds in a row start again from 0.
  void resume() { m_lost = 0; }
  //! Holds in a row so far.
  unsigned int getLostCount() const { return m_lost; }

  /*!
    Whether the fit \e T to a goal jumped from \e previous, the last period's fit to the same goal, beyond what a
    command of \e gain (the share of the residual executed per period) explains.
  */
  bool viewJumped(const vpMorphRigidTransform &T, const vpMorphRigidTransform &previous, double gain,
                  const vpCameraParameters &cam) const;
  //! A re-plan after a jump: true when allowed (counted), false when it is one too many (halted, TOO_MANY_REPLANS).
  bool allowReplan();
  //! Re-plans so far in this task.
  unsigned int getReplanCount() const { return m_replans; }

  /*!
    Whether \e current is not the target's shape (see the class description); always false without a target check.
    \e articulated: the target is the database's articulated template posed at the view's opening (its distance
    then over the template's poses). The last distance to the target is kept (getTargetDistance()).
  */
  bool targetMismatch(const vpMorphContour &current, const vpMorphContour &target, bool articulated);
  //! The last distance to the target's template (NaN before any check).
  double getTargetDistance() const { return m_targetDistance; }

  //! What the last verify() found: the first of its tests that failed, in this order, or VERIFIED.
  enum Verification {
    NOT_VERIFIED,       //!< no verification since reset()
    VERIFIED,           //!< every test passed: CONVERGED
    UNEXPLAINED,        //!< the aligned view does not explain the target (vpMorphViewAlignment::explained())
    OUTSIDE_THRESHOLDS, //!< the alignment's own residual is beyond the final thresholds
    PART_UNCHECKED,     //!< explained only in part (a part hidden or bent), and no target check to name it
    NOT_PINNED,    //!< three deviations of its rotation, translation or scale beyond the thresholds (or none known)
    TILT_UNBOUNDED //!< the tilt's estimate plus its deviations beyond the tilt's final threshold, or unknown
  };
  //! A short name of \e v ("tilt unbounded", ...).
  static const char *verificationName(Verification v);

  /*!
    CONVERGED or UNVERIFIED for an alignment \e a (normalised) at the target: CONVERGED needs it within the final
    thresholds \e rotationRad, \e translationPx and \e scalePx (the scale's error in pixels at the view's RMS radius
    \e radiusPx) by its own residual, and pinned within them (the class description), with \e pixelsPerUnit the
    camera's pixels per normalised unit, and \e tiltVerified the tilt's own verdict (true when it is not corrected).
    An alignment without a covariance (vpMorphViewAligner::PAPER) is UNVERIFIED, and so is one explained only in part
    without a target check. Why is kept (getVerification()).
  */
  Status verify(const vpMorphViewAlignment &a, double rotationRad, double translationPx, double scalePx,
                double radiusPx, double pixelsPerUnit, bool tiltVerified);
  //! What the last verify() found (NOT_VERIFIED before any in this task): why a stop at the goal is UNVERIFIED.
  Verification getVerification() const { return m_verification; }
  //! Standard deviations within the thresholds that verify() requires (3: 99.7 % of a Gaussian estimate's errors).
  static double getVerificationSigmas() { return 3.0; }

private:
  unsigned int m_maxLost = 25, m_maxReplans = 3;
  double m_jumpPx = 20.0, m_jumpRotation = 0.1;
  std::shared_ptr<const vpMorphDatabase> m_db;               // null without a target check; the recognizer's if set
  std::shared_ptr<const vpMorphPartRecognizer> m_recognizer; // its RIGID stage first, when set
  std::size_t m_index = 0;
  double m_slack = getDefaultSlack();
  unsigned int m_lost = 0, m_replans = 0;
  Status m_halted = NOT_STARTED;
  Verification m_verification = NOT_VERIFIED;
  double m_targetDistance = std::numeric_limits<double>::quiet_NaN();
};

#endif
