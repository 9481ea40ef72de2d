/*!
  \file vpMorphServoStatus.h
  \brief The statuses of the morph servo (vpServoMorph, vpMorphServoGuard).
*/
#ifndef VP_MORPH_SERVO_STATUS_H
#define VP_MORPH_SERVO_STATUS_H

/*!
  \class vpMorphServoStatus
  \ingroup group_morph_vs
  \brief The outcome of a period of the morph servo; vpServoMorph and vpMorphServoGuard derive from it, so that a user
  writes vpServoMorph::CONVERGED.

  Every status but MOVING and SUBGOAL_REACHED comes with a zero velocity.
  - <b>Holds</b> (the servo resumes when a usable view comes back): TARGET_LOST (no contour given), DEGENERATE_CONTOUR
    (too small, non-finite, unusable), UNEXPLAINED_VIEW (less than half of the view lies on its goal within the noise:
    another shape, a view the measurement cannot place), REPLANNED (the view jumped: a new plan from it).
  - <b>Stops</b> (every later period returns the same until vpServoMorph::restart() or a new target):
    CONVERGED (aligned, and the aligned view explains the target within its noise), UNVERIFIED (aligned by the
    measurement, but the view does not pin the pose within the final thresholds at its noise: a part hidden that
    leaves the pose free, a tilt the outline does not show, a view explained only in part with no target check; the
    servo cannot vouch for the pose), LOST_TOO_LONG (too many holds in a row), TOO_MANY_REPLANS, TARGET_MISMATCH (the
    view is not the target's shape).

  \code
  vpColVector ve = servo.computeControlLaw(c);
  if (servo.getStatus() == vpServoMorph::CONVERGED) { }           // done, verified
  else if (vpServoMorph::isStop(servo.getStatus()))               // a safe stop: say why
    std::cerr << vpServoMorph::statusName(servo.getStatus()) << std::endl;
  \endcode
  \sa \ref page_servo_measurement
*/
class vpMorphServoStatus
{
public:
  //! The outcome of a period (see the class description).
  enum Status {
    NOT_STARTED,        //!< No period yet.
    MOVING,             //!< Moving towards the current sub-goal.
    SUBGOAL_REACHED,    //!< A sub-goal was reached at this period; moving towards the next one.
    CONVERGED,          //!< Stop: at the target, verified.
    UNVERIFIED,         //!< Stop: at the target by the measurement, but not verified by it.
    TARGET_LOST,        //!< Hold: no contour.
    DEGENERATE_CONTOUR, //!< Hold: a contour too small, non-finite or unusable.
    UNEXPLAINED_VIEW,   //!< Hold: the view does not lie on its goal.
    REPLANNED,          //!< Hold: the view jumped; a new plan from it.
    LOST_TOO_LONG,      //!< Stop: too many holds in a row.
    TOO_MANY_REPLANS,   //!< Stop: one view jump more than allowed.
    TARGET_MISMATCH     //!< Stop: the view is not the target's shape.
  };
  //! A short name ("converged", "unexplained view"...).
  static const char *statusName(Status s);
  //! True for the statuses that stop the servo until it is restarted.
  static bool isStop(Status s);
};

#endif
