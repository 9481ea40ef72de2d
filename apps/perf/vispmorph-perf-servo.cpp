/*!
  \file vispmorph-perf-servo.cpp
  \brief Micro-benchmark of one servo iteration: what the "compute time per iteration" means, measured
  apart from rendering and from whatever else the machine runs.

  The input is real: a free camera servoes the pliers from a 150 deg start with the whole pipeline (rendered image,
  tag masked, silhouette extracted, vpServoMorph), and the contours it extracted are recorded once. The benchmarks
  then replay them:
  - BM_extract: the silhouette extraction of one 640x480 image (vpMorphContourExtractor, tag masking excluded);
  - BM_extractNoisy: the same view with the benchmark's noise set at its worst (grey-level noise of std 6, blur of
    std 1.5 px, gain 0.7, offset -25), where the mask is ragged and the edge is found under noise;
  - BM_extractShaded: the same view under the benchmark's gradient set at its steepest (a fall-off of 0.6), where the
    classes' levels follow the light's shading;
  - BM_extractCut: the same view with a card hiding 15 % of the pliers across their middle, cut in two and joined
    again (vpMorphContourExtractor::extractJoined(), as the benchmark's controllers extract every view);
  - BM_extractCutFollow: the same view followed from its own joined outline (extractJoined(I, previous), as the
    benchmark's controllers extract every view after the first): the cost of finding the object where it was;
  - BM_outlineBlur: that view's outline laid at a 1.5 px blur (vpMorphOutlineBlur, as the view aligner does once per
    goal and blur, and every period for a view sharper than its goal);
  - BM_approximate: its polygonal approximation alone (vpMorphPolygonApproximation on that image's boundary chain),
    the part of the extraction that grows with the boundary's length;
  - BM_approximateTools: the same over the boundaries of the six tools' images turned by every 15 deg (144 chains), so
    that a change to the approximation is timed on more than one outline;
  - BM_morphIteration: vpServoMorph::computeControlLaw() over the recorded run (tracked correspondence, fit,
    calibration update, Eq. 11), restarted at the end of the run; the first call of each pass also builds the
    morph and its sub-goals, so the mean includes them once per run;
  - BM_morphIterationTilt: the final approach of the run (from the last sub-goal on) with the out-of-plane
    correction on every iteration (the homography refined on the edge outlines);
  - BM_morphIterationDeformed: the final approach of a sagging wedge servoed to its template's view (recorded the
    same way, the object placed by largest overlap as in the benchmark's deformable set), where the part of the view
    off the template is left out of the aligner's robust fit;
  - BM_morphIterationDeformedFollow: the same without its first iteration (the fit to the target from the last
    sub-goal's): the periods warm-started from the previous one;
  - BM_morphStart: that first call alone (full cyclic search, morph, sequence);
  - BM_edgeBand: the fit vpServoMorph measures the edge band with on the final approach (every 8th period: the current
    outline on the target's with one common offset of its edges), and BM_edgeFit the same fit without the offset;
  - BM_planOccluded: the plan's correspondence of an occluded wedge to its taught view
  (vpMorphMatcher::matchOnRegions(): the minimal work checked on the regions, then on the outlines half a turn round),
  and BM_matchOccluded the minimal work alone (vpMorphMatcher::match()), to give the checks' cost;
  - BM_articulationEstimate: the opening of the opened pliers seen from the run's first pose, against the pliers'
    articulated template taught there (vpMorphArticulation::estimate(), once per plan), and BM_articulationPose the
    template drawn at that opening (vpMorphArticulation::pose());
  - BM_ibvs4Points: the baseline, a stock vpServo on 4 points (IBVS, current L), one computeControlLaw().
  CPU time of the fastest repetition; the table at the end gives the ratios to the IBVS baseline.

  \code
  vispmorph-perf-servo --benchmark_repetitions=5
  \endcode
*/
#include <benchmark/benchmark.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "vispmorph-perf-reporter.h"

#include <iomanip>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <visp3/core/vpImageConvert.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpVelocityTwistMatrix.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorphArticulation.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphDatabase.h>
#include <visp3/morph/vpMorphMatcher.h>
#include <visp3/morph/vpMorphOutlineBlur.h>
#include <visp3/morph/vpMorphPolygonApproximation.h>
#include <visp3/morph/vpMorphRigidTransform.h>
#include <visp3/morph_sim/vpMorphPlanarScene.h>
#include <visp3/morph_sim/vpMorphSimRobot.h>
#include <visp3/morph_sim/vpMorphTagPoseEstimator.h>
#include <visp3/morph_vs/vpServoMorph.h>
#include <visp3/visual_features/vpFeatureBuilder.h>
#include <visp3/visual_features/vpFeaturePoint.h>
#include <visp3/vs/vpServo.h>

namespace
{
//! One recorded run: the taught target, the images' tag corners, and the contours extracted on the way.
struct Recording
{
  vpMorphContour target;
  double Zd = 0.5;
  vpImage<unsigned char> firstImage;
  std::vector<vpImagePoint> firstCorners;
  vpHomogeneousMatrix firstcMo; //!< the camera's pose for the first image
  std::vector<vpMorphContour> contours;
  std::size_t finalApproach = 0; //!< index of the first contour recorded on the last sub-goal
};

// A run of the free camera from cdMc^-1 to the view of \e object taught from \e templateImage (the same image, or its
// undeformed template, against which the object is placed by largest overlap as in the benchmark's deformable set).
Recording record(const std::string &objectImage, const std::string &templateImage, const vpHomogeneousMatrix &cdMc)
{
  Recording r;
  vpMorphPlanarScene scene(objectImage), taught(templateImage);
  if (objectImage != templateImage)
    scene.setReferenceImage(templateImage, vpMorphPlanarScene::BEST_OVERLAP);
  const vpHomogeneousMatrix cdMo(0.0, 0.0, 0.5, 0, 0, 0);
  vpImage<unsigned char> I;
  vpHomogeneousMatrix cMt;
  std::vector<vpImagePoint> corners;
  taught.render(cdMo, I);
  taught.tagPoseEstimator().estimate(I, cMt, &corners);
  r.target = vpMorphTagPoseEstimator::silhouette(I, corners);
  r.Zd = cdMo[2][3];

  const vpMorphTagPoseEstimator tag = scene.tagPoseEstimator();
  vpMorphSimRobot robot(vpMorphSimRobot::FREE_CAMERA, 0.04);
  robot.setDesiredPose(cdMo);
  robot.initialiseCameraRelativeToDesired(cdMc);
  vpServoMorph servo;
  servo.setCameraParameters(scene.camera());
  servo.set_eMc(robot.eMcTrue());
  servo.setSamplingTime(0.04);
  servo.setTarget(r.target, r.Zd);
  // As the benchmark's controller: the target checked by its template (a view explained only in part, as a bent one,
  // is the target only when the check says so).
  vpMorphDatabase db;
  db.add(vpMorphTemplate("taught", r.target));
  db.calibrate(1);
  servo.getGuard().setTargetCheck(db, "taught");
  for (int it = 0; it < 400 && servo.getStatus() != vpServoMorph::CONVERGED; ++it) {
    scene.render(robot.get_cMo(), I, it);
    corners.clear();
    tag.estimate(I, cMt, &corners);
    const vpMorphContour c = vpMorphTagPoseEstimator::silhouette(I, corners);
    if (it == 0) {
      r.firstImage = I;
      r.firstCorners = corners;
      r.firstcMo = robot.get_cMo();
    }
    r.contours.push_back(c);
    robot.setVelocity(vpRobot::END_EFFECTOR_FRAME, servo.computeControlLaw(c));
    if (servo.getSubGoalIndex() + 1 < servo.getSubGoals().size())
      r.finalApproach = r.contours.size(); // not yet on the last sub-goal
  }
  if (servo.getStatus() != vpServoMorph::CONVERGED)
    throw vpException(vpException::fatalError, "vispmorph-perf-servo: the recorded run did not converge");
  return r;
}

const Recording &recording()
{
  static const Recording rec = record(std::string(VISPMORPH_DATA_DIR) + "/objects/pliers.png",
                                      std::string(VISPMORPH_DATA_DIR) + "/objects/pliers.png",
                                      vpHomogeneousMatrix(0.03, -0.02, 0, 0, 0, vpMath::rad(150)));
  return rec;
}

// The sagging wedge (its top bent down) servoed to its template's view from 60 deg away.
const Recording &deformedRecording()
{
  static const Recording rec = record(std::string(VISPMORPH_DATA_DIR) + "/objects/wedge-deformed.png",
                                      std::string(VISPMORPH_DATA_DIR) + "/objects/wedge.png",
                                      vpHomogeneousMatrix(0.02, 0.01, 0, 0, 0, vpMath::rad(60)));
  return rec;
}

void configure(vpServoMorph &servo, const Recording &r)
{
  servo.setCameraParameters(vpMorphPlanarScene::defaultCamera());
  servo.setSamplingTime(0.04);
  servo.setTarget(r.target, r.Zd);
}

// The run's first image with its tag masked, as the silhouette is extracted from it (masking not timed).
vpImage<unsigned char> maskedFirstImage(const Recording &r)
{
  vpImage<unsigned char> masked = r.firstImage;
  vpMorphTagPoseEstimator::maskTag(masked, r.firstCorners);
  return masked;
}

void BM_extract(benchmark::State &state)
{
  const vpImage<unsigned char> masked = maskedFirstImage(recording());
  vpMorphContourExtractor extractor;
  for (auto _ : state)
    benchmark::DoNotOptimize(extractor.extract(masked).size());
}

// The recording's first view of the pliers, rendered by \e scene with the faults \e f (the tag not masked).
vpImage<unsigned char> firstView(vpMorphPlanarScene &scene, const vpMorphPlanarScene::Faults &f)
{
  scene.setFaults(f);
  vpImage<unsigned char> I;
  scene.render(recording().firstcMo, I);
  return I;
}

// The extraction of the recording's first view under the faults \e f, the tag masked where its detection finds it
// (as the benchmark's controllers see their views).
void extractUnder(benchmark::State &state, const vpMorphPlanarScene::Faults &f)
{
  vpMorphPlanarScene scene(std::string(VISPMORPH_DATA_DIR) + "/objects/pliers.png");
  vpImage<unsigned char> I = firstView(scene, f);
  std::vector<vpImagePoint> corners;
  vpHomogeneousMatrix cMt;
  if (!scene.tagPoseEstimator().estimate(I, cMt, &corners))
    state.SkipWithError("tag not found in the view");
  vpMorphTagPoseEstimator::maskTag(I, corners);
  vpMorphContourExtractor extractor;
  for (auto _ : state)
    benchmark::DoNotOptimize(extractor.extract(I).size());
}

void BM_extractNoisy(benchmark::State &state)
{
  vpMorphPlanarScene::Faults f;
  f.noiseSigma = 6.0;
  f.blurSigma = 1.5;
  f.gain = 0.7;
  f.offset = -25.0;
  f.seed = 1;
  extractUnder(state, f);
}

// The recording's first view under the benchmark's gradient set at its steepest (a fall-off of 0.6 from the centre to
// the corners, toward the view's lower right): the classes' shading fitted, from two starts.
void BM_extractShaded(benchmark::State &state)
{
  vpMorphPlanarScene::Faults f;
  f.gradient = 0.6;
  f.gradientAngle = M_PI / 4.0;
  extractUnder(state, f);
}

// The recording's first view's outline laid at a blur of 1.5 px (vpMorphOutlineBlur::blurred()): what the view aligner
// pays once per goal and tenth of a pixel of blur, and every period for a view sharper than its goal.
void BM_outlineBlur(benchmark::State &state)
{
  const vpMorphContour c = vpMorphContourExtractor().extract(maskedFirstImage(recording()));
  for (auto _ : state)
    benchmark::DoNotOptimize(vpMorphOutlineBlur::blurred(c, 1.5).outline().size());
}

// The recording's first view with a card hiding 15 % of the pliers across their middle, the tag masked.
vpImage<unsigned char> cutView()
{
  vpMorphPlanarScene scene(std::string(VISPMORPH_DATA_DIR) + "/objects/pliers.png");
  vpMorphPlanarScene::Faults f;
  f.occludedShare = 0.15;
  f.occluderPosition = 0.5;
  vpImage<unsigned char> I = firstView(scene, f);
  vpMorphTagPoseEstimator::maskTag(I, scene.projectedTagCorners(recording().firstcMo));
  return I;
}

void BM_extractCut(benchmark::State &state)
{
  const vpImage<unsigned char> I = cutView();
  vpMorphContourExtractor extractor;
  if (extractor.extractJoined(I).hasRegion())
    state.SkipWithError("the card does not cut the pliers in two in this view");
  for (auto _ : state)
    benchmark::DoNotOptimize(extractor.extractJoined(I).size());
}

void BM_extractCutFollow(benchmark::State &state)
{
  const vpImage<unsigned char> I = cutView();
  vpMorphContourExtractor extractor;
  const vpMorphContour previous = extractor.extractJoined(I);
  if (previous.hasRegion())
    state.SkipWithError("the card does not cut the pliers in two in this view");
  for (auto _ : state)
    benchmark::DoNotOptimize(extractor.extractJoined(I, previous).size());
}

void BM_approximate(benchmark::State &state)
{
  const std::vector<vpImagePoint> chain = vpMorphContourExtractor().boundary(maskedFirstImage(recording()));
  for (auto _ : state)
    benchmark::DoNotOptimize(vpMorphPolygonApproximation::vertexIndices(chain).size());
  state.counters["pixels"] = double(chain.size());
}

void BM_approximateTools(benchmark::State &state)
{
  std::vector<std::vector<vpImagePoint>> chains;
  std::size_t pixels = 0;
  for (const char *tool : {"hammer", "key", "pliers", "screwdriver", "wedge", "wrench"}) {
    vpImage<unsigned char> I;
    vpImageIo::read(I, std::string(VISPMORPH_DATA_DIR) + "/objects/" + tool + ".png");
    cv::Mat M, W;
    vpImageConvert::convert(I, M);
    for (int deg = 0; deg < 360; deg += 15) {
      const cv::Mat R = cv::getRotationMatrix2D(cv::Point2f(0.5f * M.cols, 0.5f * M.rows), deg, 1.0);
      cv::warpAffine(M, W, R, M.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
      vpImage<unsigned char> J;
      vpImageConvert::convert(W, J);
      chains.push_back(vpMorphContourExtractor().boundary(J));
      pixels += chains.back().size();
    }
  }
  for (auto _ : state)
    for (const std::vector<vpImagePoint> &chain : chains)
      benchmark::DoNotOptimize(vpMorphPolygonApproximation::vertexIndices(chain).size());
  state.counters["chains"] = double(chains.size());
  state.counters["pixels"] = double(pixels);
}

void BM_morphIteration(benchmark::State &state)
{
  const Recording &r = recording();
  vpServoMorph servo;
  configure(servo, r);
  std::size_t k = 0;
  for (auto _ : state) {
    if (k == r.contours.size()) {
      servo.restart();
      k = 0;
    }
    benchmark::DoNotOptimize(servo.computeControlLaw(r.contours[k++])[0]);
  }
  state.counters["contours"] = static_cast<double>(r.contours.size());
}

// The final approach (the recorded contours from the last sub-goal on), where the bench's "morph" corrects the tilt,
// with the correction on every iteration: the homography refined on the edge outlines the recorded contours carry,
// from the previous iteration's (or from the polygons' on the first).
void BM_morphIterationTilt(benchmark::State &state)
{
  const Recording &r = recording();
  vpServoMorph servo;
  configure(servo, r);
  servo.setTiltCorrection(vpServoMorph::TILT_ALWAYS);
  std::size_t k = r.finalApproach;
  for (auto _ : state) {
    if (k == r.contours.size()) {
      servo.restart();
      k = r.finalApproach;
    }
    benchmark::DoNotOptimize(servo.computeControlLaw(r.contours[k++])[0]);
  }
  state.counters["contours"] = static_cast<double>(r.contours.size() - r.finalApproach);
  state.counters["outlines"] = r.contours.front().hasOutline() && r.target.hasOutline() ? 1.0 : 0.0;
}

// The recorded run of the sagging wedge from its iteration \e first on (the ones before it made again, untimed, at each
// pass), to the end: its final approach, where the part of the view off the template is left out of the fit.
void deformedIterations(benchmark::State &state, std::size_t first)
{
  const Recording &r = deformedRecording();
  vpServoMorph servo;
  configure(servo, r);
  std::size_t k = r.contours.size();
  for (auto _ : state) {
    if (k == r.contours.size()) {
      state.PauseTiming();
      servo.restart();
      for (k = 0; k < first; ++k)
        servo.computeControlLaw(r.contours[k]);
      state.ResumeTiming();
    }
    benchmark::DoNotOptimize(servo.computeControlLaw(r.contours[k++])[0]);
  }
  state.counters["contours"] = static_cast<double>(r.contours.size() - first);
  state.counters["rigid"] =
      !servo.getHistory().empty() && servo.getHistory().back().model == vpMorphViewAlignment::RIGID ? 1.0 : 0.0;
}

// The whole final approach (its first iteration a fit to the target from the last sub-goal's).
void BM_morphIterationDeformed(benchmark::State &state)
{
  deformedIterations(state, deformedRecording().finalApproach);
}

// The same without its first iteration: the periods that follow the last one's fit.
void BM_morphIterationDeformedFollow(benchmark::State &state)
{
  deformedIterations(state, deformedRecording().finalApproach + 1);
}

void BM_morphStart(benchmark::State &state)
{
  const Recording &r = recording();
  vpServoMorph servo;
  configure(servo, r);
  for (auto _ : state) {
    servo.restart();
    benchmark::DoNotOptimize(servo.computeControlLaw(r.contours.front())[0]);
  }
}

// The fit vpServoMorph measures the edge band with on the final approach (every 8th period): the last recorded
// contour's outline, resampled to 256 points, on the target's, 5 rounds from the identity; \e offset: with the edges'
// offset fitted too, else the plain similarity (the same fit's cost without it).
void edgeFit(benchmark::State &state, bool offset)
{
  const Recording &r = recording();
  const vpCameraParameters cam = vpMorphPlanarScene::defaultCamera();
  const vpMorphContour o = r.contours.back().toNormalized(cam).outline().resampled(256);
  const vpMorphContour t = r.target.toNormalized(cam).outline();
  for (auto _ : state) {
    double e = 0.0;
    benchmark::DoNotOptimize(
        vpMorphRigidTransform::refineOnOutline(o, t, vpMorphRigidTransform(), true, 1e-4, 5, offset ? &e : nullptr)
            .scale());
    benchmark::DoNotOptimize(e);
  }
}
void BM_edgeBand(benchmark::State &state) { edgeFit(state, true); }
void BM_edgeFit(benchmark::State &state) { edgeFit(state, false); }

// The plan's correspondence of an occluded wedge (a card over 15 % of its outline, the recorded run's first view) to
// its taught view: the minimal work alone (\e checked false), or checked on the regions and, as the regions of an
// occluded view leave the choice to the work, on the outlines half a turn round (vpMorphMatcher::matchOnRegions()).
void plan(benchmark::State &state, bool checked)
{
  const std::string wedge = std::string(VISPMORPH_DATA_DIR) + "/objects/wedge.png";
  vpMorphPlanarScene scene(wedge), taught(wedge);
  vpImage<unsigned char> I;
  std::vector<vpImagePoint> corners;
  vpHomogeneousMatrix cMt;
  taught.render(vpHomogeneousMatrix(0.0, 0.0, 0.5, 0, 0, 0), I);
  taught.tagPoseEstimator().estimate(I, cMt, &corners);
  const vpMorphContour target = vpMorphTagPoseEstimator::silhouette(I, corners);
  vpMorphPlanarScene::Faults f;
  f.occludedShare = 0.15;
  f.occluderPosition = 0.5;
  I = firstView(scene, f);
  corners.clear();
  scene.tagPoseEstimator().estimate(I, cMt, &corners);
  const vpMorphContour view = vpMorphTagPoseEstimator::silhouette(I, corners);
  vpMorphMatcher matcher;
  double gain = 0.0;
  for (auto _ : state)
    benchmark::DoNotOptimize(
        (checked ? matcher.matchOnRegions(view, target, 0.1, &gain) : matcher.match(view, target)).work());
  state.counters["gain"] = gain;
}
void BM_planOccluded(benchmark::State &state) { plan(state, true); }
void BM_matchOccluded(benchmark::State &state) { plan(state, false); }

// The pliers' silhouette (or one arm's, drawn alone in the pliers' frame) seen from the recording's first pose.
vpMorphContour pliersView(const std::string &image)
{
  vpMorphPlanarScene scene(std::string(VISPMORPH_DATA_DIR) + image);
  scene.setReferenceImage(std::string(VISPMORPH_DATA_DIR) + "/objects/pliers.png");
  vpImage<unsigned char> I;
  scene.render(recording().firstcMo, I);
  vpMorphTagPoseEstimator::maskTag(I, scene.projectedTagCorners(recording().firstcMo));
  return vpMorphContourExtractor().extract(I);
}

// The pliers' articulated template, taught from the first pose, and the opened pliers seen from there.
const vpMorphArticulation &pliersArticulation()
{
  static const vpMorphArticulation a(pliersView("/joints/pliers-part0.png"), pliersView("/joints/pliers-part1.png"),
                                     vpMorphPlanarScene(std::string(VISPMORPH_DATA_DIR) + "/objects/pliers.png")
                                         .projectedTexel(320, 240, recording().firstcMo),
                                     vpMath::rad(-8.0), vpMath::rad(60.0));
  return a;
}

void BM_articulationEstimate(benchmark::State &state)
{
  const vpMorphArticulation &a = pliersArticulation();
  const vpMorphContour opened = pliersView("/objects/pliers-deformed.png");
  double opening = 0.0;
  for (auto _ : state)
    benchmark::DoNotOptimize(opening = a.estimate(opened));
  state.counters["opening_deg"] = vpMath::deg(opening);
}

void BM_articulationPose(benchmark::State &state)
{
  const vpMorphArticulation &a = pliersArticulation();
  for (auto _ : state)
    benchmark::DoNotOptimize(a.pose(vpMath::rad(32.0)).size());
}

void BM_ibvs4Points(benchmark::State &state)
{
  vpServo task;
  task.setServo(vpServo::EYEINHAND_CAMERA);
  task.setInteractionMatrixType(vpServo::CURRENT);
  task.setLambda(0.5);
  vpFeaturePoint s[4], sd[4];
  const double xy[4][2] = {{-0.1, -0.1}, {0.1, -0.1}, {0.1, 0.1}, {-0.1, 0.1}};
  for (int i = 0; i < 4; ++i) {
    sd[i].buildFrom(xy[i][0], xy[i][1], 0.5);
    s[i].buildFrom(0.9 * xy[i][0] + 0.01, 0.9 * xy[i][1] - 0.02, 0.55);
    task.addFeature(s[i], sd[i]);
  }
  for (auto _ : state)
    benchmark::DoNotOptimize(task.computeControlLaw()[0]);
}

// The console table, then the ratios to the IBVS baseline (CPU time, fastest repetition).
class RatioReporter : public vpMorphPerfReporter
{
public:
  void Finalize() override
  {
    ConsoleReporter::Finalize();
    std::ostream &os = GetOutputStream();
    if (!m_time.count("BM_ibvs4Points"))
      return;
    const double base = m_time["BM_ibvs4Points"];
    os << "\nper call, CPU time of the fastest repetition, and ratio to a stock 4-point IBVS computeControlLaw()\n";
    for (const auto &t : m_time)
      os << std::setw(32) << std::left << t.first << std::right << std::fixed << std::setprecision(3) << std::setw(12)
         << t.second / 1000.0 << " ms" << std::setprecision(1) << std::setw(10) << t.second / base << " x\n";
  }
};
} // namespace

BENCHMARK(BM_extract)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_extractNoisy)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_extractShaded)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_extractCut)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_extractCutFollow)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_outlineBlur)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_approximate)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_approximateTools)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_morphIteration)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_morphIterationTilt)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_morphIterationDeformed)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_morphIterationDeformedFollow)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_morphStart)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_edgeBand)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_edgeFit)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_planOccluded)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_matchOccluded)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_articulationEstimate)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_articulationPose)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ibvs4Points)->Unit(benchmark::kMicrosecond);

int main(int argc, char **argv)
{
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv))
    return 1;
  try {
    recording(); // before any timing, and a clear error if the recorded run fails
  } catch (const vpException &e) {
    std::cerr << e.getStringMessage() << std::endl;
    return 1;
  }
  // OpenCV's thread pool would do part of an extraction on other threads, whose time the benchmark's CPU clock (the
  // calling thread's) leaves out; one thread makes the CPU time the whole work, as vispmorph-bench measures it.
  cv::setNumThreads(1);
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}
