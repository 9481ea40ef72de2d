/*!
  \file vpMorphJointVelocity.h
  \brief Joint velocities that move the end-effector by a commanded twist over a whole sampling period.
*/
#ifndef VP_MORPH_JOINT_VELOCITY_H
#define VP_MORPH_JOINT_VELOCITY_H

#include <functional>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpMatrix.h>

/*!
  \class vpMorphJointVelocity
  \ingroup group_morph_vs
  \brief Converts an end-effector twist into the joint velocities a joint-level driver holds for one period: solved
  on the robot's kinematic model when one is given, else with the Jacobian taken at the middle of the period.

  <b>Why.</b> A driver that holds \f$\dot q = {}^eJ_e(q_k)^+ v\f$ for the period moves the end-effector by
  \f${}^eJ_e(q(t))\,\dot q\f$, which leaves \e v as the Jacobian changes along the motion: the error is second order
  per period and adds up along a long turn into a tilt of the camera. A full 6-dof law sees that tilt and takes it
  back; a planar law does not, and the tilt about a thin object's long axis does not show in its outline.

  <b>With the kinematic model</b> (setKinematicModel(), e.g. a vpViper850's or a vpAfma6's get_fMe(q) and
  get_eJe(q)), the step is solved exactly: the joint displacement \f$\Delta q\f$ such that
  \f${}^fM_e(q_k + \Delta q) = {}^fM_e(q_k)\,\exp(v\,\Delta t)\f$, the pose a Cartesian driver holding \e v reaches
  (vpExponentialMap::direct()), by Newton's method from \f$J_k^+ v \Delta t\f$, and \f$\dot q = \Delta q / \Delta t\f$.
  It needs no history, so the first period of a start is as exact as the others.

  <b>Without it</b>, the Jacobian at the middle of the coming step is extrapolated from the last two periods' Jacobians:
  \f[ J_{mid} = J_k + \tfrac{a}{2} (J_k - J_{k-1}), \quad
      a = \frac{\langle \dot q^0 \Delta t, q_k - q_{k-1}\rangle}{\|q_k - q_{k-1}\|^2}, \quad \dot q^0 = J_k^+ v, \f]
  i.e. the change of J over the last step, scaled to the part of the coming step along it, and then
  \f$\dot q = J_{mid}^+ v\f$. This needs only what a visual servoing loop has at each period (eJe and the joint
  positions), not the robot's kinematic model. The first period after construction or reset(), after a step of no
  motion, or after a step the coming one does not continue, uses \f$J_k\f$ alone (the plain conversion); \e a is kept
  within +-kMaxStepRatio, as the change of J is only known along the last step.

  \code
  vpMorphJointVelocity joints(0.04);                       // the driver holds each velocity for 40 ms
  vpViper850 model;                                         // optional: the exact step from the robot's model
  joints.setKinematicModel({[&](const vpColVector &q) { vpHomogeneousMatrix M; model.get_fMe(q, M); return M; },
                            [&](const vpColVector &q) { vpMatrix J; model.get_eJe(q, J); return J; }});
  vpColVector qdot = joints.compute(eJe, q, servo.computeControlLaw(c));
  robot.setVelocity(vpRobot::ARTICULAR_FRAME, qdot);
  \endcode
  \sa \ref page_design_servo
*/
class vpMorphJointVelocity
{
public:
  //! The robot's forward kinematics, evaluated at any joint positions (both set, or both empty: no model).
  struct KinematicModel
  {
    std::function<vpHomogeneousMatrix(const vpColVector &q)> fMe; //!< end-effector pose in the base frame
    std::function<vpMatrix(const vpColVector &q)> eJe;            //!< 6 x n Jacobian in the end-effector frame
    //! Whether both functions are set.
    bool isSet() const { return fMe && eJe; }
  };

  //! \param samplingTime : period the velocity is held for, seconds (finite, > 0).
  explicit vpMorphJointVelocity(double samplingTime = 0.04);

  //! Period the velocity is held for (s).
  double getSamplingTime() const { return m_dt; }
  //! \throw vpMorphException::badParameterError unless finite and > 0.
  void setSamplingTime(double samplingTime);

  /*!
    Joint velocities for the end-effector twist \e ve (6-vector, end-effector frame), \e eJe (6 x n) and \e q
    (n joint positions) being this period's. Remembers eJe and q for the next period.
    \throw vpMorphException::badParameterError on inconsistent sizes or non-finite values.
  */
  vpColVector compute(const vpMatrix &eJe, const vpColVector &q, const vpColVector &ve);

  /*!
    Solves each step on \e model (an empty one: back to the extrapolated Jacobian).
    \throw vpMorphException::badParameterError when only one of its functions is set.
  */
  void setKinematicModel(const KinematicModel &model);
  //! The model the steps are solved on (empty: none).
  const KinematicModel &getKinematicModel() const { return m_model; }

  //! Forgets the previous period (a new start, or the robot was moved by something else than these velocities).
  void reset();

  //! The largest ratio of the coming step to the last one along which the Jacobian's change is extrapolated.
  static constexpr double kMaxStepRatio = 4.0;
  //! Newton's method stops when the pose reached is this close to the goal's (m, rad): a thousandth of a pixel of
  //! an 800 px camera at 1 m.
  static constexpr double kPoseTolerance = 1e-6;
  //! Newton's iterations at most: from a first-order start, two or three reach kPoseTolerance.
  static constexpr unsigned int kMaxNewtonIterations = 8;

private:
  vpColVector solveOnModel(const vpColVector &q, const vpColVector &ve, const vpColVector &qdot0) const;

  double m_dt;
  KinematicModel m_model;
  vpMatrix m_prevJ;
  vpColVector m_prevQ;
};

#endif
