/*!
  \file vpMorphBenchEvent.h
  \brief A timed fault injected into a benchmark run: dropped frames, object absent, occluder, pose jump, wrong
  template.
*/
#ifndef VP_MORPH_BENCH_EVENT_H
#define VP_MORPH_BENCH_EVENT_H

#include <string>

#include <visp3/core/vpHomogeneousMatrix.h>

/*!
  \class vpMorphBenchEvent
  \ingroup group_morph_bench
  \brief One fault of a run's schedule (value type with public fields: it only carries data), applied by
  vpMorphBench::run() at the start of iteration \e iteration, before the image of that iteration is rendered.

  Kinds, and what the loop does:
  - DROPPED_FRAMES: for \e frames iterations no image reaches the controller: the loop calls
    vpMorphBenchController::missingFrame() instead of step() (the controller is told; it never gets the previous
    image again, which it would integrate twice), and the robot holds for that period.
  - NO_OBJECT: for \e frames iterations the scene is rendered without the object
    (vpMorphPlanarScene::Faults::objectHidden); the tag is still there.
  - SUDDEN_OCCLUDER: from then on a card hides \e occludedShare of the object's outline at \e occluderPosition
    (vpMorphPlanarScene::Faults), for the rest of the run.
  - POSE_JUMP: the camera is displaced by \e cMcp (in its own frame) at once, as if the robot was bumped
    (vpMorphSimRobot::displaceCamera()); not counted in the path length.
  - WRONG_TEMPLATE: the first recognition is forced to return the template \e wrongTemplate (another
    object's), whatever \e iteration says (vpMorphBenchController::Context::forcedTemplate); controllers that do
    not recognise ignore it.

  \code
  vpMorphBenchEvent e;
  e.kind = vpMorphBenchEvent::NO_OBJECT;
  e.iteration = 20;
  e.frames = 5;                          // the object hidden for 5 periods from period 20
  scenario.events.push_back(e);
  \endcode
  \sa vpMorphBench, \ref page_hardening
*/
class vpMorphBenchEvent
{
public:
  //! The fault (see the class description).
  enum Kind {
    DROPPED_FRAMES,  //!< no image for a while
    NO_OBJECT,       //!< the object hidden for a while
    SUDDEN_OCCLUDER, //!< an occluder from then on
    POSE_JUMP,       //!< the camera bumped
    WRONG_TEMPLATE   //!< the first recognition forced to another template
  };

  Kind kind = DROPPED_FRAMES;    //!< the fault
  unsigned int iteration = 0;    //!< iteration at which it starts
  unsigned int frames = 1;       //!< DROPPED_FRAMES, NO_OBJECT: how many iterations it lasts
  double occludedShare = 0.15;   //!< SUDDEN_OCCLUDER: share of the outline hidden, (0, 0.9]
  double occluderPosition = 0.0; //!< SUDDEN_OCCLUDER: where, fraction of the perimeter, [0, 1)
  vpHomogeneousMatrix cMcp;      //!< POSE_JUMP: displacement of the camera in its own frame
  std::string wrongTemplate;     //!< WRONG_TEMPLATE: the template recognition returns

  //! True while the event acts at iteration \e it (DROPPED_FRAMES, NO_OBJECT: [iteration, iteration + frames);
  //! SUDDEN_OCCLUDER: from iteration on; POSE_JUMP and WRONG_TEMPLATE: at iteration only).
  bool activeAt(unsigned int it) const;
  //! One line, e.g. "dropped-frames@20x5", "pose-jump@30 20 mm 10 deg".
  std::string describe() const;
  //! "dropped-frames", "no-object", "sudden-occluder", "pose-jump", "wrong-template".
  static std::string kindName(Kind k);
  //! \throw vpMorphException::badParameterError for an unknown name.
  static Kind kindFromName(const std::string &name);
};

#endif
