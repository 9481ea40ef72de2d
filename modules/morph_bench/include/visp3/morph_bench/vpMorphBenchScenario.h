/*!
  \file vpMorphBenchScenario.h
  \brief One start of the benchmark: object, desired pose, start pose, scene look, image faults and calibration errors.
*/
#ifndef VP_MORPH_BENCH_SCENARIO_H
#define VP_MORPH_BENCH_SCENARIO_H

#include <string>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/morph_bench/vpMorphBenchEvent.h>
#include <visp3/morph_bench/vpMorphBenchObjectSet.h>
#include <visp3/morph_sim/vpMorphPlanarScene.h>

/*!
  \class vpMorphBenchScenario
  \ingroup group_morph_bench
  \brief Everything that makes one run repeatable: every controller of a comparison gets the same scenario.

  Value type with public fields (it only carries data). The start is given relative to the desired camera
  (cdMc) so that it does not depend on the robot; the robot places the object so that its reference
  configuration sees it at cdMo (vpMorphSimRobot::setDesiredPose()).

  <b>Identity and seeds.</b> Start \e k of object \e NAME in a set is drawn from a stream seeded by (set seed, the
  set whose starts it draws, NAME, k) only; generate() gives index i to object i mod n, start i / n (n objects), so
  adding an object, drawing more starts or sharding changes no other scenario. Each object's desired pose comes from
  (set seed, NAME) alone (desiredPose()): optical axis normal to the plane at 0.5 m, in-plane rotation uniform in
  [-180, 180] deg, offset uniform in the 20 mm disc. In the taught view the object must be entirely in view and the
  AprilTag is placed where it fits (vpMorphPlanarScene::placeTagInView(): any side, 8, 6, 5 then 4 cm); when neither
  fits, or no start shows object and tag, the scenario is a \e setup failure (its runs fail "setup", nothing else).

  <b>Sets</b> (generate(), setNames(); their order seeds them, new sets go at the end): planar, planar-hard, 6dof,
  calib, calib-no-tilt, noise, occlusion, deformable, faults, calib-wide, the scene looks (saturated, low-contrast,
  rough, gradient, plane-edge, large-distractor: the planar starts rendered with a look) and res-1280, res-320; the
  distribution of each: \ref page_benchmarks.

  A start is redrawn (from the same seeded stream, at most 1000 times) until the object and the tag are
  entirely in view, 10 px from the border (at 640 px across), at the start pose.

  \code
  std::vector<vpMorphBenchScenario> starts = vpMorphBenchScenario::generate("planar-hard", 20, 100, objects);
  std::string json = starts[3].toJson();      // replayed to the bit by vpMorphBenchScenario::fromJson()
  \endcode
  \sa vpMorphBench, \ref page_benchmarks
*/
class vpMorphBenchScenario
{
public:
  std::string set;           //!< name of the scenario set
  unsigned int index = 0;    //!< index in the set
  unsigned int seed = 0;     //!< seed of this scenario (its image noise, occluder, distractors)
  unsigned int setSeed = 0;  //!< the set seed it was drawn with (the desired poses depend on it)
  std::string object;        //!< object name
  std::string objectImage;   //!< image rendered in the scene (the deformed variant for "deformable")
  std::string templateImage; //!< image of the taught object
  std::string variant;       //!< the templates' variant: "" (the objects' images) or "rough"
  //! The articulated object's joint file (TRUTH_ARTICULATED), else empty.
  std::string jointFile;
  //! When objectImage differs from templateImage: how the truth is held (see scene()).
  vpMorphBenchObjectSet::Truth truth = vpMorphBenchObjectSet::TRUTH_OVERLAP;
  //! Why the scenario could not be set up ("tag-fits-nowhere", "object-not-in-view-at-goal", "no-start-in-view",
  //! "plane-edge-not-in-view", "no-room-for-distractor"); empty when it could.
  std::string setup;
  vpHomogeneousMatrix cdMo; //!< desired pose of the object in the camera frame
  vpHomogeneousMatrix cdMc; //!< start camera pose in the desired camera frame

  double startRotationDeg = 0;       //!< in-plane rotation of the start (deg, signed)
  double startTranslationMm = 0;     //!< in-plane translation of the start (mm)
  double startTiltDeg = 0;           //!< tilt of the start (deg)
  double startDepthChange = 0;       //!< relative depth change of the start (Z / Zd - 1)
  vpMorphPlanarScene::Faults faults; //!< image faults and scene look

  vpCameraParameters camera = vpMorphPlanarScene::defaultCamera(); //!< the true intrinsics
  unsigned int width = 640;                                        //!< image width (px)
  unsigned int height = 480;                                       //!< image height (px)
  double tagSize = 0.08;                                           //!< the tag's black-border side (m)
  double tagX = 0;                                                 //!< the tag's centre in the object frame, x (m)
  double tagY = 0;                                                 //!< the tag's centre in the object frame, y (m)
  bool tagAuto = true; //!< the tag left to the scene's default placement (tagX, tagY ignored)

  double focalScaleX = 1;                //!< intrinsics given to the controllers: px times this
  double focalScaleY = 1;                //!< and py times this
  double principalShiftU = 0;            //!< and u0 shifted by this (px)
  double principalShiftV = 0;            //!< and v0 shifted by this (px)
  vpHomogeneousMatrix eMcError;          //!< hand-eye estimate given to the controllers: eMcTrue * eMcError
  double eMcRotationTolerance = 0;       //!< the bound on eMcError's rotation the controllers are told (rad)
  double eMcTranslationTolerance = 0;    //!< the bound on eMcError's translation the controllers are told (m)
  std::vector<vpMorphBenchEvent> events; //!< timed faults of the run (set "faults")

  /*!
    The scene of this scenario: objectImage with the faults, its camera and tag. A deformed object is placed against
    templateImage by truth: TRUTH_PART and TRUTH_ARTICULATED share the template's texture frame (the undeformed part,
    or a part undone by its joint's turn, lies where the template's does), TRUTH_OVERLAP lays it where it overlaps
    the template most (vpMorphPlanarScene::BEST_OVERLAP).
  */
  vpMorphPlanarScene scene() const;
  /*!
    For TRUTH_PART: the in-plane motion W of the object frame that lays the deformed object where it overlaps its
    template most (the desired pose cdMo * W is the largest overlap's), reported beside the undeformed part's error.
    Identity otherwise.
  */
  vpHomogeneousMatrix overlapPlacement() const;
  //! The intrinsics the controllers are told, from the true ones.
  vpCameraParameters estimatedCamera(const vpCameraParameters &trueCam) const;
  //! One line describing the start, for logs and CSV files.
  std::string describe() const;

  //! The scenario set names, in the order of the protocol.
  static std::vector<std::string> setNames();
  //! The set whose starts \e set draws (itself but for calib-no-tilt, the scene looks and the resolutions).
  static std::string startSet(const std::string &set);
  //! True for the sets whose start may end tilted (6dof, calib): their pose needs the tilt observable.
  static bool needsTilt(const std::string &set);
  //! The six tools of data/objects, in a fixed order.
  static std::vector<std::string> objectNames();
  //! Desired pose of \e object for set seed \e seed (see the class description).
  static vpHomogeneousMatrix desiredPose(unsigned int seed, const std::string &object);
  //! The desired pose of \e object: its own if it has one (vpMorphBenchObjectSet::setDesiredPose()), else the above.
  static vpHomogeneousMatrix desiredPose(unsigned int seed, const vpMorphBenchObjectSet::Object &object);
  /*!
    The scenario as JSON, every number to the bit (replays a run anywhere); paths under \e base are written relative
    to it.
  */
  std::string toJson(const std::string &base = std::string()) const;
  /*!
    A scenario from toJson()'s text (one object) or from an array of them (the first); relative paths are taken from
    \e base. \throw vpMorphException::ioError for malformed text.
  */
  static vpMorphBenchScenario fromJson(const std::string &json, const std::string &base = std::string());
  //! Every scenario of a JSON array of toJson() objects. \throw vpMorphException::ioError for malformed text.
  static std::vector<vpMorphBenchScenario> listFromJson(const std::string &json,
                                                        const std::string &base = std::string());
  /*!
    The camera of \e set: its intrinsics and image size.
  */
  static void cameraOf(const std::string &set, vpCameraParameters &cam, unsigned int &width, unsigned int &height);
  //! The margin (px) that keeps object and tag in view: 10 px at 640 px across, scaled with the width.
  static double viewMargin(unsigned int width);
  /*!
    Stages \e scene at the desired pose \e cdMo: checks that the object is in view there and places the tag where it
    fits (vpMorphPlanarScene::placeTagInView(), 8, 6, 5 then 4 cm). Returns empty, or why it cannot be set up
    ("object-not-in-view-at-goal", "tag-fits-nowhere"; the tag then left where it was).
  */
  static std::string stage(vpMorphPlanarScene &scene, const vpHomogeneousMatrix &cdMo);
  /*!
    \e count scenarios of set \e set, seeded by \e seed, object i mod n of \e objects for index i (see the class
    description). The same arguments give the same scenarios; a scenario that cannot be set up has setup set.
    \throw vpMorphException::badParameterError for an unknown set, count 0 or no object.
  */
  static std::vector<vpMorphBenchScenario> generate(const std::string &set, unsigned int count, unsigned int seed,
                                                    const vpMorphBenchObjectSet &objects);
};

#endif
