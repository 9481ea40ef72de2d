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
#include <visp3/robot/vpRobot.h>

class vpFeatureMorph;
class vpServoMorph;

/*!
  \class vpMorphBenchController
  \ingroup group_morph_bench
  \brief Interface of the controllers compared by the benchmark, and their factory.

  Each controller reads its features from the rendered image only (tag corners and pose from
  vpDetectorAprilTag, silhouettes from vpMorphContourExtractor after masking the detected tag), never from the
  simulator's projections, and knows only what a real set-up would know: the estimated intrinsics and hand-eye
  transform, the geometry of the tag, the desired pose taught for the object (stock controllers) or the
  template database (VISPMorph, which recognises the object at the first frame).

  Names (create()): "morph" (vpServoMorph: the paper's Eq. 5-11 through 10 sub-goals, online hand-eye
  estimation, and the out-of-plane correction on the final approach from the homography refined on the edge
  outlines), "morph-planar" (the same without the out-of-plane correction: the paper's planar law),
  "morph-paper" (the paper's measurement as written, vpServoMorph::PAPER: elongation-vector rectification over the
  morph's correspondence, image-space rigid frames, deformation frames, per-axis thresholds; planar law),
  "morph-vpservo" (vpFeatureMorph to the final goal in a stock vpServo, EYEINHAND_CAMERA with the tilts disabled,
  current L, the camera velocity mapped by the estimated eMc), "ibvs-current", "ibvs-desired", "ibvs-mean" (4 tag
  corners, vpFeaturePoint, depth from the tag pose), "pbvs" (vpFeatureTranslation(cdMc) + vpFeatureThetaU(cdRc) from
  the tag pose), "moments" (vpFeatureMomentCommon on the silhouette's measured outline: normalised centre of gravity,
  area, c-invariants sx and sy, and alpha, as ViSP's servoMomentPolygon example, plane from the tag pose),
  "moments-planar" (the same without the c-invariants, on the camera's planar motions, as "morph-vpservo"). The
  other stock ones run EYEINHAND_L_cVe_eJe with cVe from the estimated eMc and eJe from the robot; all share the same
  constant gain.

  <b>Convergence</b> (Command::converged: the controller declares itself done, and the run ends). "morph",
  "morph-planar" and "morph-paper" when vpServoMorph reports CONVERGED. The others by a stop rule on their own error,
  written as the RMS image displacement of the points their feature stands for (the tag's corners, or the outline under
  the feature's similarity), within 3 times that displacement's own noise for 3 measured periods; the noise is 0.1 px
  per edge point (vpMorphBenchObservability's noise model) through the feature's fit: sigma sqrt(4 / n) for a similarity
  fitted to n outline points, 2 sigma / sqrt(L) for a tag corner where two fitted edges of L px meet. Every other stop
  (a vpServoMorph status other than CONVERGED that stops, a feature jump, a lost view) is zero velocity and a failure
  with its reason, never a convergence.

  <b>Faults</b> (vpMorphBenchEvent). Every controller holds (zero velocity, Command::measured false) on a
  missing frame or when its features are not in the image; the loop gives up after 10 such iterations in a row
  (feature-lost). The VISPMorph adapters add:
  - both check the recognition again: the target is wrong when the contour is beyond 1.25 x the template's
    acceptance threshold, or when the database's best template is another one, accepted, and at least 1.2 times
    cheaper. Then the object is recognised anew, the rejected templates excluded (Command::rerecognized), and the
    servo restarts towards the new template; when nothing acceptable remains the run stops with
    "target-mismatch". "morph" has vpServoMorph check (vpServoMorph::setTargetCheck()) at each new sequence
    (the first image, each re-plan) and before it reports convergence; "morph-vpservo" checks on the first image
    and every 25 measured images (1 s).
  - "morph": vpServoMorph holds while nothing is seen and resumes on the same sub-goal, stops after 8 periods
    (reason "lost-too-long", before the loop's 10); re-plans after a view jump (Command::replanned; at most 3,
    then "too-many-replans").
  - "morph-vpservo": holds while vpFeatureMorph's aligner does not explain the view (its error is then zero, which
    is not a goal reached); no sequence to re-plan, and a stock vpServo does not test its input: a jump of the
    error beyond what one step of the law explains (a bump, an occluder) stops the run ("feature-jump").

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
    vpCameraParameters cam;   //!< estimated intrinsics
    vpHomogeneousMatrix eMc;  //!< estimated hand-eye transform
    vpHomogeneousMatrix cdMo; //!< desired object pose (taught with the template)
    //! The tag as the detector saw it in the taught view (rendered at cdMo): the stock controllers' desired
    //! features, measured like their current ones (teach by showing), so that the detector's own bias cancels.
    std::vector<vpImagePoint> taughtTagCorners; //!< pixels, detector order
    vpHomogeneousMatrix taughtTagPose;          //!< cdMo as the detector estimated it
    std::vector<vpPoint> tagCorners3D;          //!< tag corners in the object frame, detector order
    int tagId = 0;                              //!< AprilTag 36h11 id
    double tagSize = 0.08;                      //!< black-border side, m
    vpHomogeneousMatrix oMt;                    //!< tag frame in the object frame
    const vpMorphDatabase *database = nullptr;  //!< templates (VISPMorph controllers)
    std::string expectedObject;                 //!< the object truly present (only to score the recognition)
    double lambda = 2.5;                        //!< gain (1/s): the same for every controller
    double samplingTime = 0.04;                 //!< s
    //! Fault injection (WRONG_TEMPLATE): the first recognition returns this template, whatever it sees.
    std::string forcedTemplate;
    //! The robot's lower joint limits (infinite for the free camera, whose "joints" are its pose).
    vpColVector jointMin;
    //! The robot's upper joint limits.
    vpColVector jointMax;
  };
  //! One command.
  struct Command
  {
    vpColVector v = vpColVector(6, 0.0);                      //!< velocity, in \e frame
    vpRobot::vpControlFrameType frame = vpRobot::JOINT_STATE; //!< the frame of \e v
    bool measured = true;      //!< features were measured in this image (false: zero velocity, hold)
    bool stop = false;         //!< the controller gave up (see reason); zero velocity
    bool converged = false;    //!< the controller's own convergence test passed
    std::string reason;        //!< short word when stop (e.g. "recognition", "unreliable-correspondence")
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
