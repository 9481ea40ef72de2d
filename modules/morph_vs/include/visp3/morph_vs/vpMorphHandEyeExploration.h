/*!
  \file vpMorphHandEyeExploration.h
  \brief The exploration turn of the morph servo: a turn about the optical axis and back that reads the tilt of the
  camera on the hand.
*/
#ifndef VP_MORPH_HAND_EYE_EXPLORATION_H
#define VP_MORPH_HAND_EYE_EXPLORATION_H

#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphRigidTransform.h>
#include <visp3/morph_vs/vpMorphHandEyeEstimator.h>
#include <visp3/morph_vs/vpMorphTiltEstimator.h>

/*!
  \class vpMorphHandEyeExploration
  \ingroup group_morph_vs
  \brief Turns the camera about its optical axis by getAngle() and back, reads the view's tilt at each period
  (vpMorphTiltEstimator::read()) and corrects the hand-eye estimate by the tilt of the camera on the hand they show.

  Why: a turn about an optical axis that eMc gets wrong by e (about the image plane's axes) tilts the camera by
  2 sin(turn / 2) e, and a thin object's outline barely shows a tilt about its long axis, so the final approach cannot
  take that back; along a turn, the object's long axis turns in the image and the readings see every axis of e.
  The plane normal seen after a turn theta about the true axis z + a (a small) from a start where it was z + n0 is
  z + a + Rot(-theta)(n0 - a) to first order: a and n0 - a are the readings' weighted least squares, their covariance
  scaled by the readings' reduced chi-square.
  - The turn runs at getSpeed() (1 rad/s); it does not start when the joints would pass a limit along it.
  - It comes back when the view comes within getBorderPx() of the image's border, and does not start there; it comes
    back when the view's tilt cannot be read: its first two views unread, or fewer than half of its views read by
    getProbeAngle().
  - A view off the turn's way (more than the jump threshold, plus getDriftPx() a period since the last view read) or
    whose area changed by getAreaChange() is not read; off the way with its area kept getJumpPeriods() times in a row,
    the robot or the object was displaced: the turn ends there (DISPLACED), uncorrected.
  - The correction is applied when its standard deviation is below getMaxDeviation() and it is at least
    getMinCorrection() and getCorrectionSigmas() deviations; then a second turn reads what the intrinsics' error left.

  \code
  vpMorphHandEyeExploration &turn = servo.getHandEyeExploration();
  turn.setAngle(M_PI / 2, 640, 480);    // before the first sequence
  \endcode
  \sa vpServoMorph, vpMorphHandEyeEstimator, \ref page_design_servo
*/
class vpMorphHandEyeExploration
{
public:
  //! What a period of the turn asks of the caller.
  enum Result {
    TURNING,  //!< the turn goes on: send the velocity
    FINISHED, //!< back where it started (eMc corrected when the readings allowed), or not started
    DISPLACED //!< the view jumped during the turn: plan again from it
  };

  //! No turn (getAngle() 0) until setAngle().
  vpMorphHandEyeExploration() = default;

  /*!
    The turn (rad, in [0, pi]; 0, the default: none) and the image's size (> 0 when the turn is not 0).
    \throw vpMorphException::badParameterError otherwise.
  */
  void setAngle(double rad, unsigned int imageWidth, unsigned int imageHeight);
  //! The turn (rad; 0: none).
  double getAngle() const { return m_angle; }
  //! Starts again (before a task): the turn pending when getAngle() > 0.
  void reset();
  //! True while the turn runs.
  bool isActive() const { return m_phase == OUT || m_phase == BACK; }
  //! The turn about the optical axis commanded by the last step() (rad; 0 when it commanded none).
  double getLastTurn() const { return m_lastTurn; }
  //! The rotation applied to eMc, about axes of the image plane (zero when none was applied).
  const vpThetaUVector &getCorrection() const { return m_correction; }

  /*!
    One period of the turn on the view \e current (pixels) and \e currentN (normalised), the target \e targetN
    (normalised, at depth \e Zd), the similarity \e currentToTarget (the start of a cold reading; null: a view the
    target does not explain, not read): reads the tilt with
    \e tilt, corrects \e handEye at the end. \e q, \e eJe, \e qMin, \e qMax: the joints (empty without), \e dt the
    sampling time, \e jumpPx the jump threshold; \e ve receives the end-effector velocity while TURNING.
  */
  Result step(const vpMorphContour &current, const vpMorphContour &currentN, const vpMorphContour &targetN, double Zd,
              const vpMorphRigidTransform *currentToTarget, const vpCameraParameters &cam, vpMorphTiltEstimator &tilt,
              vpMorphHandEyeEstimator &handEye, const vpMatrix &eJe, const vpColVector &q, const vpColVector &qMin,
              const vpColVector &qMax, double dt, double jumpPx, vpColVector &ve);

  static double getSpeed() { return 1.0; }            //!< rad/s
  static double getBorderPx() { return 40.0; }        //!< px
  static double getProbeAngle() { return 0.35; }      //!< rad
  static double getDriftPx() { return 6.0; }          //!< px a period (the turn's own tilt drifts the view)
  static double getAreaChange() { return 0.1; }       //!< relative
  static unsigned int getJumpPeriods() { return 3; }  //!< periods
  static double getMaxDeviation() { return 0.006; }   //!< rad
  static double getMinCorrection() { return 0.01; }   //!< rad, at the first turn
  static double getCorrectionSigmas() { return 5.0; } //!< standard deviations a correction must reach
  static double getRepeatAbove() { return 0.01; }     //!< rad: a correction beyond it is read again by a second turn
  static unsigned int getPasses() { return 2; }       //!< turns at most

private:
  enum Phase { NONE, OUT, BACK, DONE };
  struct Sample
  {
    double theta = 0.0;
    vpMorphTiltEstimator::Reading r;
  };
  bool command(vpMorphHandEyeEstimator &handEye, double dt, vpColVector &ve);
  double finish(vpMorphHandEyeEstimator &handEye);

  double m_angle = 0.0, m_theta = 0.0, m_lastReadTheta = 0.0, m_lastTurn = 0.0;
  unsigned int m_width = 0, m_height = 0;
  Phase m_phase = NONE;
  // The last view read (centroid, area), the turn commanded since, the views in a row displaced from it.
  double m_cx = 0.0, m_cy = 0.0, m_area = 0.0, m_turned = 0.0;
  unsigned int m_jumps = 0, m_since = 0, m_count = 0, m_pass = 0;
  vpThetaUVector m_correction{0, 0, 0};
  std::vector<Sample> m_samples;
};

#endif
