/*!
  \file vpMorphBench.h
  \brief Runs controllers on scenarios with a simulated robot and a rendered scene, and measures them.
*/
#ifndef VP_MORPH_BENCH_H
#define VP_MORPH_BENCH_H

#include <functional>
#include <string>
#include <vector>

#include <visp3/morph/vpMorphDatabase.h>
#include <visp3/morph_bench/vpMorphBenchResult.h>
#include <visp3/morph_bench/vpMorphBenchScenario.h>
#include <visp3/morph_sim/vpMorphSimRobot.h>

/*!
  \class vpMorphBench
  \ingroup group_morph_bench
  \brief The benchmark loop: identical starts for every controller, the truth kept apart from what they see.

  <b>Templates.</b> The taught view of each object is rendered at its desired pose (no fault), the tag masked
  and the silhouette extracted, exactly as at run time; the database of the six templates is calibrated for
  rejection (vpMorphDatabase::calibrate()). VISPMorph controllers recognise the object in their first image.

  <b>One run</b> (run()): the robot places the object so that its reference configuration sees it at cdMo,
  moves to the start cdMc (UNREACHABLE is a failure of every controller alike), then at each iteration: the
  truth error is recorded, the scene is rendered from the true camera (with the scenario's faults, a new noise
  realisation per frame), the controller computes a velocity from the image alone, and the robot executes it
  for one sampling period. The run ends when the controller reports convergence or gives up, when the commanded
  velocity stays below 1 mm/s and 0.1 deg/s for 10 iterations (with the default gain, errors of 0.4 mm and
  0.04 deg: the success thresholds are 1 mm and 0.5 deg), on a failure, or at the iteration budget.

  <b>Timed faults</b> (vpMorphBenchScenario::events, see vpMorphBenchEvent) are applied at the start of their
  iteration, before the truth is recorded and the image rendered: the scene's faults are switched (object hidden,
  occluder), the camera is displaced (pose jump), or the controller is told the frame is missing
  (vpMorphBenchController::missingFrame()); a wrong template is handed to the controller at the start. Iterations
  without features count as holds (vpMorphBenchResult::holds), re-plans and re-recognitions are counted too.

  Thread safety: run() is const and builds everything it changes, so runs can go on several threads.
*/
class vpMorphBench
{
public:
  struct Settings
  {
    vpMorphSimRobot::Kind robot = vpMorphSimRobot::FREE_CAMERA;
    double lambda = 2.5;               //!< gain of every controller (1/s)
    double samplingTime = 0.04;        //!< s
    unsigned int maxIterations = 600;  //!< iteration budget
    double successTranslation = 0.001; //!< m
    double successRotationDeg = 0.5;   //!< deg
    bool recordCurves = true;          //!< keep the error per iteration
  };
  //! Called after each finished run with (runs done, runs in all, the run).
  using Progress = std::function<void(std::size_t, std::size_t, const vpMorphBenchResult &)>;

  /*!
    \param dataDir : the repository's data/ folder (data/objects/<name>.png and the deformed variants).
    \throw vpMorphException for bad settings or missing images.
  */
  vpMorphBench(const std::string &dataDir, const Settings &settings);

  const Settings &settings() const { return m_settings; }
  const vpMorphDatabase &database() const { return m_db; }

  /*!
    The recognition of a scenario's first view, as the controllers see it before they move: its scene rendered from
    the start pose (the free camera's), the tag found and masked, the silhouette extracted and recognised by
    database(). \e shown, if not null, receives the silhouette (empty when there is none; then the recognition has no
    template, index npos). A check of the recognition on many starts without servoing them.
  */
  vpMorphRecognition recognizeStart(const vpMorphBenchScenario &scenario, vpMorphContour *shown = nullptr) const;

  //! One run; never throws for a controller's failure (it is the result), only for bad arguments.
  vpMorphBenchResult run(const vpMorphBenchScenario &scenario, const std::string &controller) const;
  /*!
    Every controller on every scenario, on \e threads threads (0: all cores). Results are in the order
    (scenario, controller) whatever the threads, so a run is reproducible.
  */
  std::vector<vpMorphBenchResult> runAll(const std::vector<vpMorphBenchScenario> &scenarios,
                                         const std::vector<std::string> &controllers, unsigned int threads = 0,
                                         const Progress &progress = Progress()) const;

private:
  std::string m_dataDir;
  Settings m_settings;
  vpMorphDatabase m_db;
};

#endif
