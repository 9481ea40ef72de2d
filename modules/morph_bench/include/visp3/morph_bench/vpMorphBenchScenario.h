/*!
  \file vpMorphBenchScenario.h
  \brief One start of the benchmark: object, desired pose, start pose, image faults and calibration errors.
*/
#ifndef VP_MORPH_BENCH_SCENARIO_H
#define VP_MORPH_BENCH_SCENARIO_H

#include <string>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/morph_bench/vpMorphBenchEvent.h>
#include <visp3/morph_sim/vpMorphPlanarScene.h>

/*!
  \class vpMorphBenchScenario
  \ingroup group_morph_bench
  \brief Everything that makes one run repeatable: every controller of a comparison gets the same scenario.

  Value type with public fields (it only carries data). The start is given relative to the desired camera
  (cdMc) so that it does not depend on the robot; the robot places the object so that its reference
  configuration sees it at cdMo (vpMorphSimRobot::setDesiredPose()).

  <b>Sets</b> (generate(); the protocol of DESIGN.md):
  - planar: in-plane rotation uniform in [-180, 180] deg about the desired optical axis, translation in the
    image plane of norm uniform in [0, 80] mm, same depth;
  - planar-hard: the same with |rotation| in [150, 180] deg (the classical IBVS camera retreat);
  - 6dof: planar, then the camera orbits the point of the object plane on its optical axis by a tilt in
    [0, 30] deg about a random in-plane axis, and its depth changes by a factor in [0.6, 1.4];
  - calib: planar, with intrinsics given to the controllers off by up to 20 % (each focal length scaled by
    [0.8, 1.2], principal point shifted by up to 16 px) and a hand-eye estimate off by up to 20 mm and 10 deg;
  - calib-no-tilt: calib's starts and errors (the same seeds), but the hand-eye rotation error kept about the
    optical axis only, the part the online estimation observes: it tells a tilt of the camera on the hand, which
    turns about the optical axis carry into a tilt the thin objects' outlines do not show, from the other errors;
  - noise: planar, with Gaussian noise (sigma in [1, 6] grey levels), blur (sigma in [0, 1.5] px) and an
    illumination change (gain in [0.7, 1.3], offset in [-25, 25]);
  - occlusion: planar, with a card hiding a share in [5, 20] % of the object's outline at a random place;
  - deformable: planar, the object seen is the deformed variant of its template (e.g. pliers opened wider).
  - faults: planar, with one timed fault (vpMorphBenchEvent) per start, the kinds in turn (index modulo 5:
    dropped-frames, no-object, sudden-occluder, pose-jump, wrong-template) so that 5 n starts give n of each:
    dropped frames for 3-8 iterations or the object absent for 2-6 iterations from iteration 15-40; an occluder
    of 10-25 % of the outline appearing at iteration 15-40; a jump of 20 mm in a random in-plane direction and
    10 deg about the optical axis (either sign) at iteration 15-40; recognition forced to another object's
    template (drawn among the five others) at the first frame. The object in turn comes from the start's index
    divided by 5, so each fault kind meets different objects.

  A start is redrawn (from the same seeded stream, at most 1000 times) until the object and the tag are
  entirely in view, 10 px from the border, at the start pose: a start that shows nothing is no comparison.
*/
class vpMorphBenchScenario
{
public:
  std::string set;           //!< name of the scenario set
  unsigned int index = 0;    //!< index in the set
  unsigned int seed = 0;     //!< seed of this scenario (set seed and index)
  std::string object;        //!< object name (its template is data/objects/<object>.png)
  std::string objectImage;   //!< image rendered in the scene (the deformed variant for "deformable")
  std::string templateImage; //!< image of the taught object
  //! The articulated object's joint (DATA/joints/NAME.json, vispmorph-make-data) when it has one, else empty.
  std::string jointFile;
  vpHomogeneousMatrix cdMo;  //!< desired pose of the object in the camera frame
  vpHomogeneousMatrix cdMc;  //!< start camera pose in the desired camera frame

  double startRotationDeg = 0;       //!< in-plane rotation of the start (deg, signed)
  double startTranslationMm = 0;     //!< in-plane translation of the start (mm)
  double startTiltDeg = 0;           //!< tilt of the start (deg)
  double startDepthChange = 0;       //!< relative depth change of the start (Z / Zd - 1)
  vpMorphPlanarScene::Faults faults; //!< image faults of the scene

  double focalScaleX = 1, focalScaleY = 1;         //!< intrinsics given to the controllers: px, py times these
  double principalShiftU = 0, principalShiftV = 0; //!< and u0, v0 shifted by these (px)
  vpHomogeneousMatrix eMcError;                    //!< hand-eye estimate given to the controllers: eMcTrue * eMcError
  std::vector<vpMorphBenchEvent> events;           //!< timed faults of the run (set "faults")

  /*!
    The scene of this scenario: objectImage with the faults, placed against templateImage when the two differ
    (vpMorphPlanarScene::setReferenceImage(), BEST_OVERLAP): a deformed object is aligned when it overlays its
    template as well as a rigid placement can, and the truth error is measured to that pose. Not where its part
    drawn undeformed lies on the template's (SHARED_FRAME): which part of a bent tool stayed still does not show
    in an image, so no controller could be held to it.
  */
  vpMorphPlanarScene scene() const;
  //! The intrinsics the controllers are told, from the true ones.
  vpCameraParameters estimatedCamera(const vpCameraParameters &trueCam) const;
  //! One line describing the start, for logs and CSV files.
  std::string describe() const;

  //! The scenario set names, in the order of the protocol.
  static std::vector<std::string> setNames();
  //! The six objects of data/objects, in a fixed order.
  static std::vector<std::string> objectNames();
  /*!
    Desired pose of an object: optical axis normal to the plane at 0.5 m, with an in-plane offset and a
    rotation that differ per object (the taught view of each object is different).
    \throw vpMorphException::notFoundError for an unknown object.
  */
  static vpHomogeneousMatrix desiredPose(const std::string &object);
  /*!
    \e count scenarios of set \e set, seeded by \e seed, objects taken in turn from objectNames(), images
    read from \e dataDir (the repository's data/ folder). The same arguments give the same scenarios.
    \throw vpMorphException::badParameterError for an unknown set or count 0; notFoundError for missing images.
  */
  static std::vector<vpMorphBenchScenario> generate(const std::string &set, unsigned int count, unsigned int seed,
                                                    const std::string &dataDir);
};

#endif
