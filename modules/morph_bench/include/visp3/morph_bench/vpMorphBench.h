/*!
  \file vpMorphBench.h
  \brief Runs controllers on scenarios with a simulated robot and a rendered scene, and measures them.
*/
#ifndef VP_MORPH_BENCH_H
#define VP_MORPH_BENCH_H

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <visp3/morph/vpMorphDatabase.h>
#include <visp3/morph/vpMorphPartRecognizer.h>
#include <visp3/morph_bench/vpMorphBenchController.h>
#include <visp3/morph_bench/vpMorphBenchObjectSet.h>
#include <visp3/morph_bench/vpMorphBenchObservability.h>
#include <visp3/morph_bench/vpMorphBenchResult.h>
#include <visp3/morph_bench/vpMorphBenchScenario.h>
#include <visp3/morph_sim/vpMorphSimRobot.h>

/*!
  \class vpMorphBench
  \ingroup group_morph_bench
  \brief The benchmark loop: identical starts for every controller, the truth kept apart from what they see.

  <b>Templates.</b> The taught view of each object is rendered at its desired pose
  (vpMorphBenchScenario::desiredPose(), from the set seed) by the scenario's camera, the tag placed where it fits
  and masked, the silhouette extracted, exactly as at run time; the database of all the objects' templates is
  calibrated for rejection (vpMorphDatabase::calibrate()). One database per template variant (the objects', the
  rough set's) and camera, taught on first use (prepare() does it ahead). VISPMorph controllers recognise the
  object in their first image.

  <b>One run</b> (run()): a scenario that could not be set up is a "setup" failure of every controller, with its
  reason (vpMorphBenchResult::setup); so is a taught view whose tag the detector does not find. Otherwise the robot
  places the object so that its reference configuration sees it at cdMo, moves to the start cdMc (UNREACHABLE is a
  failure of every controller alike), then at each iteration: the truth error is recorded, the scene is rendered
  from the true camera (with the scenario's faults, a new noise realisation per frame), the controller computes a
  velocity from the image alone, and the robot executes it for one sampling period. The run ends when the
  controller reports convergence (Command::converged) or gives up, when the commanded velocity stays below 1 mm/s
  and 0.1 deg/s for 10 iterations (with the default gain, errors of 0.4 mm and 0.04 deg: the success thresholds are
  1 mm and 0.5 deg), on a failure, or at the iteration budget (600 periods of 40 ms: 24 s).

  <b>Timed faults</b> (vpMorphBenchScenario::events, see vpMorphBenchEvent) are applied at the start of their
  iteration, before the truth is recorded and the image rendered: the scene's faults are switched (object hidden,
  occluder), the camera is displaced (pose jump), or the controller is told the frame is missing
  (vpMorphBenchController::missingFrame()); a wrong template is handed to the controller at the start. Iterations
  without features count as holds (vpMorphBenchResult::holds), re-plans and re-recognitions are counted too.

  Thread safety: run() is const; the databases are taught under a lock, so runs can go on several threads.

  \code
  vpMorphBenchObjectSet objects = vpMorphBenchObjectSet::tools("data", "out/objects");
  vpMorphBench bench(objects, 100, vpMorphBench::Settings());         // the set seed fixes the starts
  std::vector<vpMorphBenchScenario> starts = vpMorphBenchScenario::generate("planar", 10, 100, objects);
  std::vector<vpMorphBenchResult> results = bench.runAll(starts, {"morph", "pbvs"});
  \endcode
  \sa vpMorphBenchReport, \ref page_benchmarks
*/
class vpMorphBench
{
public:
  //! The run's settings, the same for every controller.
  struct Settings
  {
    vpMorphSimRobot::Kind robot = vpMorphSimRobot::FREE_CAMERA; //!< the robot simulated
    double lambda = 2.5;                                        //!< gain of every controller (1/s)
    double samplingTime = 0.04;                                 //!< s
    unsigned int maxIterations = 600;                           //!< iteration budget
    double successTranslation = 0.001;                          //!< m
    double successRotationDeg = 0.5;                            //!< deg
    bool recordCurves = true;                                   //!< keep the error per iteration
    //! The databases' distance (vpMorphShapeDistance::fromName()); empty: vpMorphDatabase's default.
    std::string recognitionModel;
  };
  //! Called after each finished run with (runs done, runs in all, the run).
  using Progress = std::function<void(std::size_t, std::size_t, const vpMorphBenchResult &)>;

  /*!
    \param objects : the objects (their templates are taught from their images).
    \param seed : the set seed of the scenarios (it fixes the desired poses, so the taught views).
    \throw vpMorphException for bad settings or an empty object set.
  */
  vpMorphBench(const vpMorphBenchObjectSet &objects, unsigned int seed, const Settings &settings);
  ~vpMorphBench();

  //! The settings.
  const Settings &settings() const { return m_settings; }
  //! The objects.
  const vpMorphBenchObjectSet &objects() const { return m_objects; }
  //! The set seed.
  unsigned int seed() const { return m_seed; }
  /*!
    The calibrated database of the templates of \e variant ("" or "rough") taught with the camera of set \e set
    (taught on first use).
  */
  const vpMorphDatabase &database(const std::string &variant = "", const std::string &set = "planar") const;
  /*!
    What the taught view of \e object (of \e variant, with the camera of \e set) lets a servo know of its pose
    (vpMorphBenchObservability; the runs are scored modulo its symmetry and tallied apart when it is unobservable);
    null when the object could not be taught.
  */
  const vpMorphBenchObservability *observability(const std::string &object, const std::string &variant = "",
                                                 const std::string &set = "planar") const;
  //! Teaches the databases \e scenarios need, ahead of the runs.
  void prepare(const std::vector<vpMorphBenchScenario> &scenarios) const;

  /*!
    The recognition of a scenario's first view, as the controllers see it before they move: its scene rendered from
    the start pose (the free camera's), the tag found and masked, the candidate silhouettes extracted and the one its
    database's vpMorphPartRecognizer recognises best chosen. \e shown, if not null, receives the silhouette (empty when
    there is none; then the recognition has no template, index npos), \e stage the stage that answered. A check of
    the recognition on many starts without servoing them.
  */
  vpMorphRecognition recognizeStart(const vpMorphBenchScenario &scenario, vpMorphContour *shown = nullptr,
                                    vpMorphPartRecognizer::Stage *stage = nullptr) const;

  //! One period of a run as a picture of it needs it (run()'s observer).
  struct Frame
  {
    unsigned int iteration;                         //!< from 0
    const vpImage<unsigned char> &image;            //!< the camera image the controller was given
    const vpMorphBenchController &controller;       //!< after its step on \e image
    const vpMorphBenchController::Command &command; //!< what the controller commanded
    vpHomogeneousMatrix cMo;                        //!< the truth
  };
  //! Called at each period of a run (see run()).
  using FrameObserver = std::function<void(const Frame &)>;

  /*!
    One run; never throws for a controller's failure or a scenario's set-up (it is the result), only for bad
    arguments. \e observer, if given, is called at each period the controller was given an image (not on a dropped
    frame), after its step: a video of the run (vispmorph-bench --video). Its exceptions end the run and reach the
    caller.
  */
  vpMorphBenchResult run(const vpMorphBenchScenario &scenario, const std::string &controller,
                         const FrameObserver &observer = FrameObserver()) const;
  /*!
    Every controller on every scenario, on \e threads threads (0: all cores). Results are in the order
    (scenario, controller) whatever the threads, so a run is reproducible.
  */
  std::vector<vpMorphBenchResult> runAll(const std::vector<vpMorphBenchScenario> &scenarios,
                                         const std::vector<std::string> &controllers, unsigned int threads = 0,
                                         const Progress &progress = Progress()) const;

private:
  struct Taught;
  vpMorphBenchResult runOnce(const vpMorphBenchScenario &scenario, const std::string &controller,
                             const FrameObserver &observer) const;
  const Taught &taught(const std::string &variant, const std::string &set) const;

  vpMorphBenchObjectSet m_objects;
  unsigned int m_seed;
  Settings m_settings;
  mutable std::mutex m_mutex;
  mutable std::map<std::string, std::unique_ptr<Taught>> m_taught;
};

#endif
