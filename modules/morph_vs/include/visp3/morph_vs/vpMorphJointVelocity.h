/*!
  \file vpMorphJointVelocity.h
  \brief Joint velocities that move the end-effector by a commanded twist over a whole sampling period.
*/
#ifndef VP_MORPH_JOINT_VELOCITY_H
#define VP_MORPH_JOINT_VELOCITY_H

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpMatrix.h>

/*!
  \class vpMorphJointVelocity
  \ingroup group_morph_vs
  \brief Converts an end-effector twist into the joint velocities a joint-level driver holds for one period, with
  the Jacobian taken at the middle of the period instead of its start.

  <b>Why.</b> A driver that holds \f$\dot q = {}^eJ_e(q_k)^+ v\f$ for the period moves the end-effector by
  \f${}^eJ_e(q(t))\,\dot q\f$, which leaves \e v as the Jacobian changes along the motion: the error is second order
  per period and adds up along a long turn into a tilt of the camera. A full 6-dof law sees that tilt and takes it
  back; a planar law does not, and the tilt about a thin object's long axis does not show in its outline.

  <b>How.</b> The Jacobian at the middle of the coming step is extrapolated from the last two periods' Jacobians:
  \f[ J_{mid} = J_k + \tfrac{a}{2} (J_k - J_{k-1}), \quad
      a = \frac{\langle \dot q^0 \Delta t, q_k - q_{k-1}\rangle}{\|q_k - q_{k-1}\|^2}, \quad \dot q^0 = J_k^+ v, \f]
  i.e. the change of J over the last step, scaled to the part of the coming step along it, and then
  \f$\dot q = J_{mid}^+ v\f$. This needs only what a visual servoing loop has at each period (eJe and the joint
  positions), not the robot's kinematic model. The first period after construction or reset(), after a step of no
  motion, or after a step the coming one does not continue, uses \f$J_k\f$ alone (the plain conversion); \e a is kept
  within +-kMaxStepRatio, as the change of J is only known along the last step.

  \code
  vpMorphJointVelocity joints(0.04);                       // the driver holds each velocity for 40 ms
  vpColVector qdot = joints.compute(eJe, q, servo.computeControlLaw(c));
  robot.setVelocity(vpRobot::ARTICULAR_FRAME, qdot);
  \endcode
  \sa \ref page_design_servo
*/
class vpMorphJointVelocity
{
public:
  //! \param samplingTime : period the velocity is held for, seconds (finite, > 0).
  explicit vpMorphJointVelocity(double samplingTime = 0.04);

  //! Period the velocity is held for (s).
  double samplingTime() const { return m_dt; }
  //! \throw vpMorphException::badParameterError unless finite and > 0.
  void setSamplingTime(double samplingTime);

  /*!
    Joint velocities for the end-effector twist \e ve (6-vector, end-effector frame), \e eJe (6 x n) and \e q
    (n joint positions) being this period's. Remembers eJe and q for the next period.
    \throw vpMorphException::badParameterError on inconsistent sizes or non-finite values.
  */
  vpColVector compute(const vpMatrix &eJe, const vpColVector &q, const vpColVector &ve);

  //! Forgets the previous period (a new start, or the robot was moved by something else than these velocities).
  void reset();

  //! The largest ratio of the coming step to the last one along which the Jacobian's change is extrapolated.
  static constexpr double kMaxStepRatio = 4.0;

private:
  double m_dt;
  vpMatrix m_prevJ;
  vpColVector m_prevQ;
};

#endif
