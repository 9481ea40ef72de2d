/*!
  \file vpMorphBenchResult.h
  \brief The metrics of one run of one controller on one scenario.
*/
#ifndef VP_MORPH_BENCH_RESULT_H
#define VP_MORPH_BENCH_RESULT_H

#include <limits>
#include <string>
#include <vector>

#include <visp3/morph_bench/vpMorphBenchScenario.h>

/*!
  \class vpMorphBenchResult
  \ingroup group_morph_bench
  \brief Outcome and metrics of one run (value type with public fields: it only carries data).

  Success: the final pose error against the simulator's truth is below the thresholds (1 mm and 0.5 deg by
  default), the controller's target (the object for silhouette controllers, the tag for tag controllers) never
  left the view, and the run ended within the iteration budget. Otherwise \e failure says why, the first
  event that applies in this order: setup (the scenario could not be set up, see \e setup), unreachable (start out
  of the robot's reach), out-of-view, diverged (the camera left 0.15-1.5 m from the plane), feature-lost (features
  not measured in 10 successive images), recognition (the object was rejected or taken for another), a controller's
  own stop (its status, e.g. unreliable-correspondence, lost-too-long, too-many-replans, target-mismatch,
  deformation-unresolved; joint-limit when a joint stopped at its limit in the period before, which moved the camera
  off the command), joint-limit (a joint limit was hit), budget (still moving at the last iteration), final-error
  (stopped away from the goal).

  False convergence (\e falseConverged): the controller declared itself done (vpMorphBenchController::Command::
  converged) while the truth is out of tolerance. A stop that is not a convergence is never a false convergence; it
  is scored by its truth as any run (a safe stop at the goal is a success that declared no convergence), except that
  out-of-view, diverged and feature-lost fail whatever the truth.

  \code
  vpMorphBenchResult r = bench.run(scenario, "morph");
  if (!r.success) std::cout << r.failure << (r.falseConverged ? " (false convergence)" : "") << std::endl;
  \endcode
  \sa vpMorphBenchReport, \ref page_benchmarks
*/
class vpMorphBenchResult
{
public:
  vpMorphBenchScenario scenario; //!< the start
  std::string robot;             //!< robot kind name
  std::string controller;        //!< controller name
  bool success = false;          //!< see the class description
  std::string failure = "none";  //!< see the class description
  std::string setup;             //!< failure "setup": why (vpMorphBenchScenario::setup, or the taught view's tag)
  bool converged = false;        //!< the controller declared itself done
  bool falseConverged = false;   //!< converged with the truth out of tolerance
  //! The taught view's symmetry (vpMorphBenchObservability::symmetryOrder(): 1 none, 0 continuous); the errors are
  //! measured modulo it.
  unsigned int symmetry = 1;
  //! Why the view's pose cannot be bounded at pixel noise (vpMorphBenchObservability::reason()), empty when it can.
  std::string unobservable;
  //! What the controller's verification found where it stopped at its goal, converged or not
  //! (vpMorphBenchController::Command::verification: "verified", "tilt-unbounded"...); empty otherwise.
  std::string verification;
  unsigned int iterations = 0; //!< iterations run
  int convergedIteration = -1; //!< first iteration after which the truth error stayed below the thresholds
  double pathLength = 0;       //!< camera centre path, m
  double straightLine = 0;     //!< distance between start and desired camera centres, m
  double finalTranslation = 0; //!< final error (simulator truth), m, measured at the object
  double finalRotation = 0;    //!< final error (simulator truth), rad
  //! The desired pose the final errors are measured against: 0 the scenario's, k its k-th equally good placement
  //! (vpMorphPlanarScene::alternativePlacements(): an opened pliers laid by its other arm), the nearest.
  unsigned int goal = 0;
  bool tagMeasured = false;       //!< the final image showed the tag
  double finalTagTranslation = 0; //!< final error measured through the AprilTag (true intrinsics), m
  double finalTagRotation = 0;    //!< rad
  std::string recognized;         //!< template chosen by recognition (VISPMorph controllers), else empty
  double measureMs = 0;           //!< mean feature measurement time per iteration (CPU time of the run's thread)
  double controlMs = 0;           //!< mean control-law time per iteration (CPU time of the run's thread)
  double maxControlMs = 0;        //!< worst control-law time
  //! Compute (measure + control, CPU ms) of each measured period but the first (its recognition and plan).
  std::vector<double> periodMs;
  //! The measure's part of each of periodMs (CPU ms).
  std::vector<double> periodMeasureMs;
  double runCpuS = 0;              //!< CPU time of the whole run on its thread, rendering and set-up included (s)
  double tagSize = 0;              //!< the scene's tag (black border), m
  double taughtTagTranslation = 0; //!< the tag pose's error in the taught view (the tag truth's accuracy), m
  double taughtTagRotation = 0;    //!< rad
  //! TRUTH_PART deformable runs: the final error against the largest overlap's placement (NaN otherwise).
  double finalOverlapTranslation = std::numeric_limits<double>::quiet_NaN();
  double finalOverlapRotation = std::numeric_limits<double>::quiet_NaN(); //!< rad
  unsigned int jointLimitHits = 0;                                        //!< steps clipped at a joint limit
  double maxSpeed = 0;                  //!< largest commanded translation speed (end-effector twist), m/s
  double maxRotationSpeed = 0;          //!< largest commanded rotation speed, rad/s
  unsigned int holds = 0;               //!< iterations without features (missing frames included): zero velocity
  unsigned int replans = 0;             //!< re-plans after a view jump (VISPMorph)
  unsigned int rerecognitions = 0;      //!< re-recognitions after a wrong target (VISPMorph)
  std::vector<double> curveTranslation; //!< truth error per iteration (against the goal), m
  std::vector<double> curveRotation;    //!< rad

  //! path length / straight line, or NaN when the straight line is shorter than 1 mm (pure rotation).
  double pathRatio() const;
  //! True when no template was chosen or the one chosen is the object's.
  bool recognitionCorrect() const { return recognized.empty() || recognized == scenario.object; }
};

#endif
