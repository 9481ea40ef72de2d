#include <visp3/morph_vs/vpMorphViewAligner.h>

#include "vpMorphParameterCheck.h"

#include <cmath>
#include <limits>

#include <visp3/core/vpException.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphHomography.h>
#include <visp3/morph/vpMorphOutlineBlur.h>

namespace
{
// Share of the view's area that must lie on the goal's, and of the goal's outline that must lie on the view's, for
// the fit to stand for the view: below, the part laid on the goal is not the larger part of the object (or the view
// was shrunk onto a part of the goal).
const double kBreakdown = 0.5;
// Points of the outlines whose regions' overlap is measured (a few pixels apart).
const std::size_t kRegionPoints = 128;
// IRLS rounds of the correspondence's robust fit: Tukey's weights settle in a few rounds from the least squares.
const unsigned int kRobustIterations = 30;

// The model of a fit that stands for the view, from the shares of the view's samples in runs of outliers longer than
// the noise makes, off the goal's region (\e outside) and on it (\e inside): none, rigid; else the side they lie on
// tells a part bent out of the goal from a part hidden (an occluder's edge inside the goal).
vpMorphViewAlignment::Model modelOf(double outside, double inside)
{
  if (outside + inside == 0.0)
    return vpMorphViewAlignment::RIGID;
  return outside > inside ? vpMorphViewAlignment::PART_BENT : vpMorphViewAlignment::PART_HIDDEN;
}

// Whether the outline fit of \e view on \e goal adds a common edge offset: polygons keep it (their vertices lie on
// boundary pixels, not on the edges); measured outlines where a clipped level may have moved them.
bool outlineFitOffset(const vpMorphContour &view, const vpMorphContour &goal)
{
  return !(view.hasOutline() && goal.hasOutline()) || vpMorphViewAligner::edgesMayBeOffset(view, goal);
}
} // namespace

vpMorphViewAligner::vpMorphViewAligner() : m_cam(getDefaultCameraParameters())
{
  for (unsigned int i = 0; i < 4; ++i)
    m_last.covariance[i][i] = std::numeric_limits<double>::infinity();
}

void vpMorphViewAligner::setCameraParameters(const vpCameraParameters &cam)
{
  m_cam = cam;
  if (!m_goalN.empty())
    setGoal(vpMorphContour(m_goalN));
}

void vpMorphViewAligner::setGoal(const vpMorphContour &goal)
{
  if (goal.empty())
    throw vpMorphException(vpMorphException::badParameterError, "vpMorphViewAligner::setGoal: empty goal");
  m_goalPx = goal.units() == vpMorphContour::PIXEL ? goal : goal.toPixels(m_cam);
  m_goalN = goal.units() == vpMorphContour::PIXEL ? goal.toNormalized(m_cam) : goal;
  m_goals.clear();
  m_goals.emplace(0, m_goalN);
  const vpMorphContour &o = m_goalN.outline();
  m_goalRegion = o.size() > kRegionPoints ? o.resampled(kRegionPoints) : o;
  m_tracker.reset();
  m_haveStart = m_haveHomography = false;
  m_last = vpMorphViewAlignment();
  for (unsigned int i = 0; i < 4; ++i)
    m_last.covariance[i][i] = std::numeric_limits<double>::infinity();
}

void vpMorphViewAligner::setStart(const vpMorphRigidTransform &currentToGoal, double sigmaPx)
{
  vpMorphParameterCheck::nonNegative(sigmaPx, "vpMorphViewAligner::setStart", "sigma");
  m_start = currentToGoal;
  m_startSigma = sigmaPx / std::max(m_cam.get_px(), m_cam.get_py());
  m_haveStart = true;
  m_startPredicted = true;
}

void vpMorphViewAligner::turnStart(double rad)
{
  if (!std::isfinite(rad))
    throw vpMorphException(vpMorphException::badParameterError, "vpMorphViewAligner::turnStart: non-finite turn");
  // A point of the new view is where the last view had it turned by rad about the optical axis.
  if (m_haveStart && rad != 0.0)
    m_start = m_start * vpMorphRigidTransform(rad, 0.0, 0.0);
  m_startPredicted = m_haveStart;
}

void vpMorphViewAligner::reset()
{
  m_tracker.reset();
  m_haveStart = m_haveHomography = false;
}

void vpMorphViewAligner::setMethod(Method m)
{
  m_method = m;
  reset();
}

double vpMorphViewAligner::overlapShare(const vpMorphRigidTransform &T, const vpMorphContour &currentN) const
{
  const vpMorphContour &o = currentN.outline();
  const vpMorphContour laid = T.apply(o.size() > kRegionPoints ? o.resampled(kRegionPoints) : o);
  const double a = laid.area();
  return a > 0.0 && std::isfinite(a) ? laid.overlapArea(m_goalRegion) / a : 0.0;
}

vpMorphViewAligner::BlurredGoal &vpMorphViewAligner::atOneBlur(vpMorphContour &currentN)
{
  BlurredGoal &plain = m_goals.at(0);
  const double pixel = std::sqrt(m_cam.get_px() * m_cam.get_py());
  const double goalBlur = m_goalN.outlineBlur() * pixel, viewBlur = currentN.outlineBlur() * pixel; // pixels
  if (!(goalBlur > 0.0) || !(viewBlur > 0.0))
    return plain; // a blur unknown: compared as measured
  // The view's size on the goal's: the start's scale, else the regions'.
  const double s = m_haveStart ? m_start.scale() : std::sqrt(m_goalN.regionArea() / currentN.regionArea());
  if (!(s > 0.0) || !std::isfinite(s))
    return plain;
  // Blurs add in variance; laying an outline at a blur integrates its pixels once more (pixelVariance()).
  const double goalExtra2 = s * s * viewBlur * viewBlur - goalBlur * goalBlur - vpMorphOutlineBlur::pixelVariance();
  const double viewExtra2 = goalBlur * goalBlur / (s * s) - viewBlur * viewBlur - vpMorphOutlineBlur::pixelVariance();
  // A blur b moves an edge of curvature k by k b^2 / 2: under the outlines' floor for the finest edge the pixel grid
  // draws (k = 1/px) while b^2 < 2 floor, and the two are compared as measured.
  const double smallest2 = 2.0 * outlineSigmaFloorPx();
  // Where a blur leaves no outline (a part thinner than it everywhere), the two are compared as measured too.
  if (goalExtra2 > smallest2) {
    const long step = std::lround(std::sqrt(goalExtra2) / blurStepPx());
    auto it = m_goals.find(step);
    if (it == m_goals.end()) {
      vpMorphContour laid = m_goalN;
      try {
        laid = vpMorphOutlineBlur::blurred(m_goalPx, double(step) * blurStepPx()).toNormalized(m_cam);
      } catch (const vpException &) {
      }
      it = m_goals.emplace(step, laid).first;
    }
    return it->second;
  }
  if (viewExtra2 > smallest2) {
    try {
      currentN = vpMorphOutlineBlur::blurred(currentN.toPixels(m_cam), std::sqrt(viewExtra2)).toNormalized(m_cam);
    } catch (const vpException &) {
    }
  }
  return plain;
}

vpMorphViewAlignment vpMorphViewAligner::fromFit(const vpMorphRigidTransform &T, const vpMorphOutlineFit &fit,
                                                 const vpMorphContour &currentN, bool cold, bool measured) const
{
  vpMorphViewAlignment a;
  const double px = std::max(m_cam.get_px(), m_cam.get_py());
  a.transform = T;
  a.covariance = fit.getCovariance();
  a.sigmaPx = fit.getSigma() * px;
  a.edgeOffsetPx = fit.getOffset() * px;
  a.inlierShare = fit.getInlierShare();
  a.outsideShare = fit.getOutsideShare();
  a.insideShare = fit.getInsideShare();
  a.fromCorrespondence = cold;
  // The model test: beyond the breakdown point, or a robust scale that no edge noise makes, the fit does not stand for
  // the view; else its runs of outliers (vpMorphOutlineFit::getOutsideShare()) are a part the goal does not have.
  a.overlapShare = overlapShare(T, currentN);
  a.goalCoverage = fit.getGoalCoverage();
  if (a.overlapShare < kBreakdown || !(a.goalCoverage >= kBreakdown) ||
      !(a.sigmaPx <= (measured ? outlineSigmaLimitPx() : polygonSigmaLimitPx())))
    a.model = vpMorphViewAlignment::UNEXPLAINED;
  else
    a.model = modelOf(a.outsideShare, a.insideShare);
  return a;
}

vpMorphRigidTransform vpMorphViewAligner::correspondenceStart(const vpMorphContour &currentN, vpMorphViewAlignment &a)
{
  const vpMorphCorrespondence &corr = m_tracker.update(currentN, m_goalN);
  a.work = m_tracker.work();
  a.margin = m_tracker.lastSource() == vpMorphCorrespondenceTracker::FULL ? m_tracker.margin()
                                                                          : std::numeric_limits<double>::quiet_NaN();
  if (m_method == PAPER)
    return vpMorphRigidTransform::fitElongation(currentN, m_goalN, corr, true);
  // Polygon vertices lie on the pixel grid: the robust scale is floored at half a pixel.
  return vpMorphRigidTransform::fitLeastSquares(currentN, m_goalN, corr, true, vpMorphRigidTransform::TUKEY,
                                                kRobustIterations, normalisedPixels(polygonSigmaFloorPx()));
}

namespace
{
// The similarity of least squares from the points (x, y) to their images (X, Y) (closed-form 2-D Procrustes), about
// the points' centroid.
vpMorphRigidTransform procrustes(const std::vector<double> &x, const std::vector<double> &y,
                                 const std::vector<double> &X, const std::vector<double> &Y)
{
  const double n = double(x.size());
  double mx = 0, my = 0, mX = 0, mY = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    mx += x[k] / n;
    my += y[k] / n;
    mX += X[k] / n;
    mY += Y[k] / n;
  }
  double dot = 0, cross = 0, var = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double px = x[k] - mx, py = y[k] - my, qx = X[k] - mX, qy = Y[k] - mY;
    dot += px * qx + py * qy;
    cross += px * qy - py * qx;
    var += px * px + py * py;
  }
  return vpMorphRigidTransform(std::atan2(cross, dot), mX - mx, mY - my, std::hypot(dot, cross) / var, mx, my);
}
} // namespace

bool vpMorphViewAligner::perspective(const vpMorphContour &currentN, const vpMorphContour &goalN,
                                     vpMorphViewAlignment &a, bool warmOnly)
{
  // A view that no similarity explains may be the goal seen tilted: a homography (refined on the outlines) that lays
  // the larger part of it on the goal within the edges' noise says so. The similarity is then the homography's own,
  // over the view's outline.
  const bool measured = currentN.hasOutline() && goalN.hasOutline();
  const double limit = normalisedPixels(measured ? outlineSigmaLimitPx() : polygonSigmaLimitPx());
  const double floor = normalisedPixels(measured ? outlineSigmaFloorPx() : polygonSigmaFloorPx());
  const bool offset = edgesMayBeOffset(currentN, goalN);
  // One start's homography and the tests a similarity's fit passes, on the view it lays: the larger part of it on the
  // goal and of the goal on it (eight parameters bend many an outline onto part of another), and its model.
  struct Candidate
  {
    vpMorphHomography G;
    vpMorphViewAlignment::Model model = vpMorphViewAlignment::UNEXPLAINED;
    double outside = 0.0, inside = 0.0, coverage = 0.0, sigma = 0.0;
    vpMatrix covariance;
    std::vector<double> residuals;
  };
  auto tryStart = [&](const vpMorphHomography &G0, bool fromPolygons, Candidate &c) {
    try {
      c.G = fromPolygons ? vpMorphHomography::fit(currentN, m_goalN, m_tracker.update(currentN, m_goalN), floor) : G0;
      c.G =
          vpMorphHomography::refine(currentN.outline(), goalN.outline(), c.G, floor, vpMorphHomography::kDefaultSamples,
                                    vpMorphHomography::kDefaultIterations, offset);
      if (!(c.G.inlierShare() >= kBreakdown && c.G.residual() <= limit))
        return false;
      const vpMorphContour laid = c.G.apply(currentN.outline());
      vpMorphOutlineFit check(goalN);
      check.setMinimumSigma(floor);
      check.setFineWidth(fineWidth(currentN, measured));
      check.setMaxIterations(1);
      check.setEdgeOffset(outlineFitOffset(currentN, goalN));
      check.fit(laid, vpMorphRigidTransform());
      const vpMorphContour region = laid.size() > kRegionPoints ? laid.resampled(kRegionPoints) : laid;
      const double area = region.area();
      const double overlap = area > 0.0 ? region.overlapArea(m_goalRegion) / area : 0.0;
      if (!(check.getGoalCoverage() >= kBreakdown) || !(overlap >= kBreakdown) || !(check.getSigma() <= limit))
        return false;
      c.outside = check.getOutsideShare();
      c.inside = check.getInsideShare();
      c.model = modelOf(c.outside, c.inside);
      c.coverage = check.getGoalCoverage();
      // How well the goal pins the laid view's similarity: the uncertainty of the homography's similarity part.
      c.covariance = check.getCovariance();
      c.residuals = check.getResiduals();
      c.sigma = check.getSigma();
      return true;
    } catch (const vpException &) {
      return false;
    }
  };
  // From the last period's homography when the view was already seen tilted. The motion since is unknown: where that
  // start leaves part of the view off the goal it may have settled in the wrong place (as a similarity's warm fit may),
  // and the start from the similarity competes; from the correspondence's polygon fit only for a view no similarity
  // explains and no other start does. When two stand, the lower robust cost at one scale (the better fit's noise) wins.
  std::vector<Candidate> found;
  Candidate c;
  if (m_haveHomography && tryStart(m_homography, false, c))
    found.push_back(c);
  const bool warmWhole = !found.empty() && found.front().model == vpMorphViewAlignment::RIGID;
  if (!warmOnly && !warmWhole && tryStart(vpMorphHomography(a.transform.toMatrix()), false, c))
    found.push_back(c);
  if (!warmOnly && found.empty() && !a.explained() && tryStart(vpMorphHomography(), true, c))
    found.push_back(c);
  if (found.empty())
    return false;
  const Candidate *best = &found.front();
  if (found.size() == 2) {
    const double sigma = std::min(found[0].sigma, found[1].sigma);
    if (vpMorphOutlineFit::cost(found[1].residuals, sigma) < vpMorphOutlineFit::cost(found[0].residuals, sigma))
      best = &found[1];
  }
  // The simpler model first: a part hidden or bent is read under the homography only where no similarity reads the
  // view at all (a similarity's part model is not traded for a tilt that bends the part onto the goal).
  if (best->model != vpMorphViewAlignment::RIGID && (warmOnly || a.explained()))
    return false;
  const vpMorphHomography &G = best->G;
  const vpMorphContour o =
      currentN.outline().size() > kRegionPoints ? currentN.outline().resampled(kRegionPoints) : currentN.outline();
  std::vector<double> X(o.size()), Y(o.size());
  for (std::size_t k = 0; k < o.size(); ++k)
    if (!G.apply(o.x(k), o.y(k), X[k], Y[k]))
      return false;
  a.transform = procrustes(o.xs(), o.ys(), X, Y);
  a.goalCoverage = best->coverage;
  a.covariance = best->covariance;
  m_homography = G;
  m_haveHomography = true;
  a.model = best->model;
  a.perspective = true;
  a.outsideShare = best->outside;
  a.insideShare = best->inside;
  a.inlierShare = G.inlierShare();
  a.sigmaPx = G.residual() * std::max(m_cam.get_px(), m_cam.get_py());
  a.overlapShare = overlapShare(a.transform, currentN);
  a.fromCorrespondence = false;
  return true;
}

vpMorphViewAlignment vpMorphViewAligner::align(const vpMorphContour &current)
{
  if (m_goalPx.empty())
    throw vpMorphException(vpMorphException::badParameterError, "vpMorphViewAligner::align: no goal; call setGoal()");
  vpMorphViewAlignment result;
  for (unsigned int i = 0; i < 4; ++i)
    result.covariance[i][i] = std::numeric_limits<double>::infinity();
  vpMorphContour currentN;
  const vpMorphContour *goalN = &m_goalN; // the goal at the view's blur
  try {
    if (current.empty())
      throw vpMorphException(vpMorphException::badContourError, "empty view");
    currentN = current.units() == vpMorphContour::PIXEL ? current.toNormalized(m_cam) : current;
    BlurredGoal &goal = m_method == PAPER ? m_goals.at(0) : atOneBlur(currentN);
    goalN = &goal.goalN;
    if (m_method == PAPER) {
      vpMorphViewAlignment a;
      a.transform = correspondenceStart(currentN, a);
      a.model = vpMorphViewAlignment::RIGID;
      a.inlierShare = 1.0;
      a.fromCorrespondence = true;
      for (unsigned int i = 0; i < 4; ++i)
        a.covariance[i][i] = std::numeric_limits<double>::infinity();
      result = a;
    } else if (m_haveHomography && perspective(currentN, *goalN, result = m_last, true)) {
      // Seen tilted at the last period: the homography followed from there explains it again.
    } else {
      vpMorphOutlineFit &fit = goal.fit;
      const bool measured = currentN.hasOutline() && goalN->hasOutline();
      fit.setEdgeOffset(outlineFitOffset(currentN, *goalN));
      fit.setMinimumSigma(normalisedPixels(measured ? outlineSigmaFloorPx() : polygonSigmaFloorPx()));
      fit.setFineWidth(fineWidth(currentN, measured));
      // Residuals beyond the noise's limit are not the goal's edges seen again: the fit settles on the part that is.
      fit.setMaximumSigma(normalisedPixels(measured ? outlineSigmaLimitPx() : polygonSigmaLimitPx()));
      bool haveWarm = false;
      vpMorphViewAlignment warm;
      std::vector<double> warmResiduals;
      if (m_haveStart) {
        const vpMorphRigidTransform T = fit.fit(currentN, m_start, m_startSigma);
        warm = fromFit(T, fit, currentN, false, measured);
        warmResiduals = fit.getResiduals();
        haveWarm = true;
        result = warm;
      }
      // From the last alignment alone (the motion since unknown), a fit that leaves part of the view off the goal
      // may have settled in the wrong place, dropping the samples it did not reach: the correspondence's fit competes.
      const bool warmExplained = warm.explained(); // false without a warm start
      if (!warmExplained || (!m_startPredicted && warm.model != vpMorphViewAlignment::RIGID)) {
        vpMorphViewAlignment cold;
        const vpMorphRigidTransform T0 = correspondenceStart(currentN, cold);
        // Beside an explained warm fit, the correspondence's start is fitted as it is: the search's other starts
        // look for the largest rigid part of a view no start explains.
        const vpMorphRigidTransform T = warmExplained ? fit.fit(currentN, T0) : fit.search(currentN, T0);
        vpMorphViewAlignment c = fromFit(T, fit, currentN, true, measured);
        c.work = cold.work;
        c.margin = cold.margin;
        // The two fits compared at one scale, the smaller robust one (the better fit's noise).
        const double sigma = std::min(warm.sigmaPx, c.sigmaPx) / std::max(m_cam.get_px(), m_cam.get_py());
        if (!haveWarm || fit.cost(sigma) <= vpMorphOutlineFit::cost(warmResiduals, sigma))
          result = c;
      }
    }
  } catch (const vpException &) {
    result = vpMorphViewAlignment(); // a view the fits cannot take (degenerate, collapsed)
    for (unsigned int i = 0; i < 4; ++i)
      result.covariance[i][i] = std::numeric_limits<double>::infinity();
  }
  // A view the similarity leaves parts of off the goal may be the goal seen tilted rather than a part hidden or bent.
  if (result.model != vpMorphViewAlignment::RIGID && m_method == OUTLINE && !currentN.empty())
    perspective(currentN, *goalN, result);
  if (!result.perspective)
    m_haveHomography = false;
  if (result.explained()) {
    // The next view moved by an unknown share of this alignment: its residuals' scale is measured anew there (a
    // start at this one's noise would keep only the samples that did not move). setStart() may say better.
    m_start = result.transform;
    m_startSigma = 0.0;
    m_haveStart = true;
  }
  m_startPredicted = false;
  m_last = result;
  return result;
}
