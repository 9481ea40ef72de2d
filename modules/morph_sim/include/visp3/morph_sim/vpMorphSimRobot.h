/*!
  \file vpMorphSimRobot.h
  \brief Headless, deterministic eye-in-hand robots for the benchmark: free camera, Viper850, Afma6.
*/
#ifndef VP_MORPH_SIM_ROBOT_H
#define VP_MORPH_SIM_ROBOT_H

#include <memory>
#include <string>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/core/vpVelocityTwistMatrix.h>
#include <visp3/robot/vpRobot.h>

/*!
  \class vpMorphSimRobot
  \ingroup group_morph_sim
  \brief A simulated eye-in-hand robot stepped by a fixed sampling period, with a camera mounted by a true eMc
  that the controller may not know.

  Kinds:
  - FREE_CAMERA: a free-flying end-effector (vpSimulatorCamera integrates its velocity); its 6 "joints" are
    the end-effector velocity, eJe = identity; no joint limits.
  - VIPER850: the 6-axis PUMA-like arm, with ViSP's vpViper850 kinematic model and joint limits.
  - AFMA6: the gantry, with ViSP's vpAfma6 model and joint limits (its wrist joints cannot turn the camera by
    180 deg about the optical axis from one configuration: it is reported, not hidden; setDesiredPoseMidway() puts
    such a start within reach). Its reference configuration has joint 5 at 45 deg:
    at 90 deg (the tool looking straight down) joints 4 and 6 are aligned, the wrist singularity.

  <b>Why not vpSimulatorViper850 / vpSimulatorAfma6 directly:</b> they integrate the joint velocity in a
  wall-clock thread, so two runs differ and a run lasts as long as the simulated motion. This class
  integrates the same ViSP kinematic models (fMe(q), eJe(q), joint limits) with q += qdot * dt at each
  setVelocity() call, so runs are bit-for-bit repeatable and as fast as the CPU allows; each call is one
  sampling period, like a real robot loop.

  <b>Hand-eye:</b> the camera truly sits at eMcTrue() on the end-effector. Camera-frame velocity commands are
  converted with eMcNominal(), the transform the robot controller believes (by default the true one; set an
  error with setCameraMount()), exactly like a real robot whose eMc is miscalibrated. A servo loop that works
  in joint space builds its own cVe from its own eMc estimate and uses get_eJe().

  <b>Joint limits:</b> a step that would cross a limit stops the joint on the limit; status() becomes
  JOINT_LIMIT (sticky until reset by a new start pose) and jointLimitHits() counts such steps.

  \code
  vpMorphSimRobot robot(vpMorphSimRobot::VIPER850, 0.04);
  robot.setDesiredPose(cdMo);                                    // the object placed for the goal
  robot.initialiseCameraRelativeToDesired(cdMc);                 // the start
  for (;;) {
    scene.render(robot.get_cMo(), I);                            // what the camera sees
    robot.setVelocity(vpRobot::END_EFFECTOR_FRAME, servo.computeControlLaw(extract(I)));
  }
  \endcode
  \sa vpMorphPlanarScene, \ref page_simulation
*/
class vpMorphSimRobot
{
public:
  //! The robot simulated.
  enum Kind {
    FREE_CAMERA, //!< a free-flying end-effector
    VIPER850,    //!< ViSP's Viper850 arm
    AFMA6        //!< ViSP's Afma6 gantry
  };
  //! The outcome of the commands so far.
  enum Status {
    OK,          //!< Every command so far executed in full.
    JOINT_LIMIT, //!< A command was clipped at a joint limit.
    UNREACHABLE  //!< The last requested start pose is out of the reference configuration's reach within the limits.
  };

  /*!
    \param kind : robot.
    \param samplingTime : integration period, seconds (> 0), one setVelocity() call.
  */
  explicit vpMorphSimRobot(Kind kind, double samplingTime = 0.04);
  ~vpMorphSimRobot();
  //! A copy in the same state (its own kinematic model).
  vpMorphSimRobot(const vpMorphSimRobot &other);
  //! Copies the state of \e other.
  vpMorphSimRobot &operator=(const vpMorphSimRobot &other);

  //! The robot simulated.
  Kind kind() const { return m_kind; }
  //! "camera", "viper850" or "afma6".
  static std::string kindName(Kind kind);
  //! The integration period (s).
  double samplingTime() const { return m_dt; }

  /*!
    The true camera mount eMcTrue and the one the robot controller uses for camera-frame commands.
    Defaults: for the arms, ViSP's eMc of the robot model; for the free camera, a 10 cm offset along z.
    The end-effector stays where it is, so the true camera moves with the new mount: call it before
    setDesiredPose().
  */
  void setCameraMount(const vpHomogeneousMatrix &eMcTrue, const vpHomogeneousMatrix &eMcNominal);
  //! The true camera mount.
  const vpHomogeneousMatrix &eMcTrue() const { return m_eMcTrue; }
  //! The mount the robot controller uses for camera-frame commands.
  const vpHomogeneousMatrix &eMcNominal() const { return m_eMcNominal; }
  //! A transform offset by (dt metres along x, y, z and dr rad about an axis (1,1,1)/sqrt 3): a hand-eye error.
  static vpHomogeneousMatrix perturbed(const vpHomogeneousMatrix &eMc, double dt, double dr);

  /*!
    Places the object in the fixed frame so that the camera sees it at \e cdMo with the robot in its reference
    configuration (referenceJointPositions()), then puts the robot there. Call once per scenario: afterwards
    the object does not move, and start poses are set with initialiseCameraRelativeToObject().
  */
  void setDesiredPose(const vpHomogeneousMatrix &cdMo);
  /*!
    Like setDesiredPose(), but the reference configuration sees the object from half-way between the desired camera
    and the start camera \e cdMc (half the screw motion from one to the other), so that the start and the goal
    straddle it; then puts the robot at the desired pose. For a wrist that cannot turn the camera about its axis
    all the way round: the Afma6 turns it by about 100 deg either way from one configuration, so from the goal's
    configuration a start turned by more than that is out of reach, while from half-way turns up to about 200 deg
    are within it. Returns false and sets status UNREACHABLE when the desired pose has no inverse-kinematics
    solution within the limits. Then initialiseCameraRelativeToDesired(cdMc) places the start.
  */
  bool setDesiredPoseMidway(const vpHomogeneousMatrix &cdMo, const vpHomogeneousMatrix &cdMc);
  /*!
    Moves the robot (instantly, in position) so that the true camera sees the object at \e cMo: inverse
    kinematics with the true eMc, in the configuration of the reference joints (referenceJointPositions(): the
    goal's), the joints reached from them by a straight joint path that crosses no singularity (no shoulder, elbow
    or wrist flip, which no servo makes on its way to the goal). Returns false and sets status UNREACHABLE (robot not
    moved) when that configuration has no solution within the joint limits. Resets the path length, the step counter
    and the status.
  */
  bool initialiseCameraRelativeToObject(const vpHomogeneousMatrix &cMo);
  /*!
    Start pose given relative to the desired camera: the camera is put at cdMc (pose of the start camera in
    the desired camera frame), i.e. it sees the object at cMo = cdMc^-1 * cdMo. Same result and status as
    initialiseCameraRelativeToObject(). Needs setDesiredPose() first.
  */
  bool initialiseCameraRelativeToDesired(const vpHomogeneousMatrix &cdMc);
  /*!
    A sudden, uncommanded displacement of the camera (the robot or its mount was bumped): the true camera moves
    instantly by \e cMcp, expressed in its current frame (the new camera pose is fMc * cMcp), through inverse
    kinematics in the current joints' configuration for the arms. Not a commanded motion: the path length, the step
    count and the status are kept. Returns false, robot not moved, when that configuration does not reach the new
    pose within the limits.
  */
  bool displaceCamera(const vpHomogeneousMatrix &cMcp);
  //! The desired pose given to setDesiredPose().
  const vpHomogeneousMatrix &get_cdMo() const { return m_cdMo; }
  //! Sets the joint positions directly (checked against the limits); resets path length and status.
  void setJointPositions(const vpColVector &q);

  /*!
    One sampling period of motion. \e frame is vpRobot::CAMERA_FRAME (6-vector twist of the camera, converted
    with eMcNominal()), vpRobot::END_EFFECTOR_FRAME (twist of the end-effector) or vpRobot::JOINT_STATE (joint
    velocities). Cartesian commands go through the pseudo-inverse of eJe(q).
    \return the status after the step.
  */
  Status setVelocity(vpRobot::vpControlFrameType frame, const vpColVector &v);

  //! Robot Jacobian in the end-effector frame at the current joints.
  vpMatrix get_eJe() const;
  /*!
    The arm's Jacobian in the end-effector frame at the joint positions \e q (its kinematic model).
    \throw vpMorphException::badParameterError for the free camera (its joints are its pose, not a kinematic
    chain) or unless \e q holds 6 finite values.
  */
  vpMatrix get_eJe(const vpColVector &q) const;
  //! Twist transform from the end-effector to the TRUE camera (what a perfectly calibrated controller would use).
  vpVelocityTwistMatrix get_cVe() const;
  //! Pose of the end-effector in the fixed frame.
  vpHomogeneousMatrix get_fMe() const;
  //! The arm's end-effector pose at the joint positions \e q; throws as get_eJe(const vpColVector &).
  vpHomogeneousMatrix get_fMe(const vpColVector &q) const;
  //! Pose of the true camera in the fixed frame.
  vpHomogeneousMatrix get_fMc() const;
  //! True object pose in the camera frame (the simulator's ground truth).
  vpHomogeneousMatrix get_cMo() const;
  //! Pose of the object in the fixed frame.
  const vpHomogeneousMatrix &get_fMo() const { return m_fMo; }
  //! The joint positions (the free camera: its pose as 6 values).
  vpColVector getJointPositions() const;
  //! The joints' lower limits (infinite: none).
  vpColVector getJointMin() const;
  //! The joints' upper limits (infinite: none).
  vpColVector getJointMax() const;
  //! The configuration at which setDesiredPose() puts the desired camera pose, and in which the starts are placed.
  vpColVector referenceJointPositions() const;
  //! Changes it (6 finite joint positions within the limits); for the free camera, ignored.
  void setReferenceJointPositions(const vpColVector &q);

  //! The status (sticky since the last start pose).
  Status status() const { return m_status; }
  //! Steps clipped at a joint limit since the last start pose.
  unsigned int jointLimitHits() const { return m_limitHits; }
  //! setVelocity() calls since the last start pose.
  unsigned int steps() const { return m_steps; }
  //! Length of the path travelled by the true camera centre since the last start pose, metres.
  double cameraPathLength() const { return m_path; }

private:
  struct Model;
  void checkPose(const vpHomogeneousMatrix &M, const char *what) const;
  void checkModelJoints(const vpColVector &q, const char *what) const;
  // Joints putting the true camera at fMc within the limits, in the configuration of q (in: the seed); the arms only.
  bool solveCamera(const vpHomogeneousMatrix &fMc, vpColVector &q) const;
  // Moves the robot to put the true camera at fMc in the configuration of qFrom, false if it has none within the
  // limits.
  bool placeCamera(const vpHomogeneousMatrix &fMc, const vpColVector &qFrom);
  // The sampling of the joint path solveCamera() checks (rad): det eJe of the Viper850 and the Afma6 changes sign
  // only across a singular configuration, which one degree of the joint turning most cannot step over.
  static constexpr double kPlacementJointStep = 1.7453292519943295e-2;

  Kind m_kind;
  double m_dt;
  std::unique_ptr<Model> m_model;
  vpHomogeneousMatrix m_eMcTrue, m_eMcNominal, m_fMo, m_cdMo;
  Status m_status = OK;
  unsigned int m_limitHits = 0, m_steps = 0;
  double m_path = 0.0;
  vpColVector m_qRef;
};

#endif
