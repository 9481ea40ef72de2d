// vispmorph-bench --video: each run of the command recorded as a camera records it and as a person watches it.
#ifndef VISPMORPH_BENCH_VIDEO_H
#define VISPMORPH_BENCH_VIDEO_H

#include <string>
#include <vector>

#include <visp3/morph_bench/vpMorphBench.h>

/*!
  Runs every controller on every scenario, one run at a time, and writes each run in
  \e out/video/SET-INDEX-CONTROLLER/:
  - frames/frame-NNNN.png and frames.avi: the camera images the controller was given, numbered from 0 (a dropped
    frame has none): what a real camera would have recorded;
  - overlay/overlay-NNNN.png and overlay.avi (vpVideoWriter, MJPG, at the bench's frame rate): the same images with
    the controller's state drawn (vpServoMorph::draw() for "morph" and "morph-planar"; s* and s for
    "morph-vpservo"; the others the image alone) and a caption (run, period, truth error);
  - db.json and camera.xml: the templates and the camera the run used, what vispmorph-replay needs to replay the frames.
  Prints each run's outcome and the vispmorph-replay command of its frames. Returns the exit status (0).
*/
int recordRuns(const vpMorphBench &bench, const std::vector<vpMorphBenchScenario> &scenarios,
               const std::vector<std::string> &controllers, const std::string &out);

#endif
