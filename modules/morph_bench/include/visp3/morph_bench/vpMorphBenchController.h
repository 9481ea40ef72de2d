/*!
  \file vpMorphBenchController.h
  \brief A controller under comparison: features measured from the rendered image, a velocity for the robot.
*/
#ifndef VP_MORPH_BENCH_CONTROLLER_H
#define VP_MORPH_BENCH_CONTROLLER_H

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/core/vpPoint.h>
#include <visp3/morph/vpMorphDatabase.h>
#include <visp3/morph/vpMorphPartRecognizer.h>
#include <visp3/morph_vs/vpMorphJointVelocity.h>
#include <visp3/robot/vpRobot.h>

class vpFeatureMorph;
class vpServoMorph;

/*!
  \class vpMorphBenchController
  \ingroup group_morph_bench
  \brief Interface of the controllers compared by the benchmark, and their factory.

  Each controller reads its features from the rendered image only (tag corners and pose from vpDetectorAprilTag,
  silhouettes from vpMorphContourExtractor after masking the detected tag) and knows only what a real set-up would
  know: the estimated intrinsics and hand-eye transform, the tag's geometry, the desired pose taught for the object
  (stock controllers) or the template database (VISPMorph, which recognises the object at the first frame).

  Names (create()): "morph" (vpServoMorph through 10 sub-goals, online hand-eye estimation, tilt correction on the
  final approach), "morph-planar" (the same, the paper's planar law), "morph-paper" (vpServoMorph::PAPER),
  "morph-vpservo" (vpFeatureMorph in a stock vpServo, EYEINHAND_CAMERA, tilts disabled, the tilt levelled by
  vpMorphTiltEstimator), "ibvs-current",
  "ibvs-desired", "ibvs-mean" (4 tag corners, vpFeaturePoint), "pbvs" (vpFeatureTranslation(cdMc) and
  vpFeatureThetaU(cdRc) from the tag pose), "moments" (vpFeatureMomentCommon on the measured outline) and
  "moments-planar" (its planar features). All share one constant gain.

  <b>Convergence</b> (Command::converged ends the run): the VISPMorph servos when vpServoMorph reports CONVERGED; the
  others by a stop rule on their own error, the RMS image displacement of the points their feature stands for, within
  3 times its own noise for 3 measured periods ("morph-vpservo": and its tilt verified, else a stop, "unverified").
  Every other stop is zero velocity and a failure with its reason
  (Command::reason), never a convergence.

  <b>Faults</b>: a missing frame or features out of the image are a hold (zero velocity, Command::measured false);
  the VISPMorph adapters also check the recognition again and re-recognise (Command::rerecognized), and "morph"
  re-plans after a view jump (Command::replanned). The rules and their constants: \ref page_benchmarks.

  \code
  std::unique_ptr<vpMorphBenchController> c = vpMorphBenchController::create("ibvs-current");
  c->start(ctx);                                            // intrinsics, eMc, the taught features, the database
  vpMorphBenchController::Command cmd = c->step(I, robot.get_eJe(), robot.getJointPositions());
  robot.setVelocity(cmd.frame, cmd.v);
  \endcode
  \sa vpMorphBench, \ref page_benchmarks
*/
class vpMorphBenchController
{
public:
  //! What a controller is told at the start of a run.
  struct Context
  {
    vpCameraParameters cam;             //!< estimated intrinsics
    vpHomogeneousMatrix eMc;            //!< estimated hand-eye transform
    double eMcRotationTolerance = 0;    //!< the stated bound on eMc's rotation error (rad; 0: calibrated)
    double eMcTranslationTolerance = 0; //!< the stated bound on eMc's translation error (m; 0: calibrated)
    vpHomogeneousMatrix cdMo;           //!< desired object pose (taught with the template)
    //! The tag as the detector saw it in the taught view (rendered at cdMo): the stock controllers' desired
    //! features, measured like their current ones (teach by showing), so that the detector's own bias cancels.
    std::vector<vpImagePoint> taughtTagCorners; //!< pixels, detector order
    vpHomogeneousMatrix taughtTagPose;          //!< cdMo as the detector estimated it
    std::vector<vpPoint> tagCorners3D;          //!< tag corners in the object frame, detector order
    int tagId = 0;                              //!< AprilTag 36h11 id
    double tagSize = 0.08;                      //!< black-border side, m
    vpHomogeneousMatrix oMt;                    //!< tag frame in the object frame
    const vpMorphDatabase *database = nullptr;  //!< templates (VISPMorph controllers)
    //! The first view's recognition over \e database (VISPMorph controllers; null: the database's own)
    const vpMorphPartRecognizer *recognizer = nullptr;
    std::string expectedObject; //!< the object truly present (only to score the recognition)
    double lambda = 2.5;        //!< gain (1/s): the same for every controller
    double samplingTime = 0.04; //!< s
    //! Fault injection (WRONG_TEMPLATE): the first recognition returns this template, whatever it sees.
    std::string forcedTemplate;
    //! The robot's lower joint limits (infinite for the free camera, whose "joints" are its pose).
    vpColVector jointMin;
    //! The robot's upper joint limits.
    vpColVector jointMax;
    //! The arm's kinematic model (valid during the run), which a joint-level driver's step is solved on; empty for
    //! the free camera, whose "joints" are its pose.
    vpMorphJointVelocity::KinematicModel robotModel;
  };
  //! One command.
  struct Command
  {
    vpColVector v = vpColVector(6, 0.0);                      //!< velocity, in \e frame
    vpRobot::vpControlFrameType frame = vpRobot::JOINT_STATE; //!< the frame of \e v
    bool measured = true;   //!< features were measured in this image (false: zero velocity, hold)
    bool stop = false;      //!< the controller gave up (see reason); zero velocity
    bool converged = false; //!< the controller's own convergence test passed
    std::string reason;     //!< short word when stop (e.g. "recognition", "unreliable-correspondence")
    //! At a stop at the goal (converged or not), what the controller's verification found
    //! (vpMorphServoGuard::verificationName(), dashed: "verified", "tilt-unbounded"...); empty otherwise.
    std::string verification;
    bool replanned = false;    //!< the view jumped and the controller re-planned from it (zero velocity)
    bool rerecognized = false; //!< the target was found wrong and the object recognised anew
    double measureMs = 0;      //!< CPU time to measure the features (tag masking for silhouettes excluded)
    double controlMs = 0;      //!< CPU time of the control law (vpMorphThreadCpuClock)
  };

  virtual ~vpMorphBenchController() = default;
  //! The controller's name (one of names()).
  virtual std::string name() const = 0;
  //! Starts a run (resets every state).
  virtual void start(const Context &ctx) = 0;
  //! One iteration on the image \e I with the robot Jacobian \e eJe at the joint positions \e q.
  virtual Command step(const vpImage<unsigned char> &I, const vpMatrix &eJe, const vpColVector &q) = 0;
  /*!
    One iteration without an image (a dropped frame): the controller is told, rather than given the previous
    image again, which it would integrate twice. Default: hold (not measured, zero velocity).
  */
  virtual Command missingFrame();
  //! Name of the recognised template (VISPMorph), empty otherwise.
  virtual std::string recognizedObject() const { return std::string(); }
  //! For pictures of a run (vpMorphBench::FrameObserver): the servo of "morph" and "morph-planar", else null.
  virtual const vpServoMorph *servo() const { return nullptr; }
  //! For pictures of a run: the current and desired features (s, s*) of "morph-vpservo", else nulls.
  virtual std::pair<const vpFeatureMorph *, const vpFeatureMorph *> features() const { return {nullptr, nullptr}; }

  //! The names create() accepts, in report order.
  static std::vector<std::string> names();
  //! \throw vpMorphException::notFoundError for an unknown name.
  static std::unique_ptr<vpMorphBenchController> create(const std::string &name);
};

#endif
