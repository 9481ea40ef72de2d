#include <visp3/morph_vs/vpMorphViewAligner.h>

#include <cmath>
#include <limits>

#include <visp3/core/vpException.h>
#include <visp3/morph/vpMorphException.h>

namespace
{
// Share of the view's area that must lie on the goal's for the fit to stand for the view: beyond, the part laid on
// the goal is not the larger part of the object.
const double kBreakdown = 0.5;
// Points of the outlines whose regions' overlap is measured (a few pixels apart).
const std::size_t kRegionPoints = 128;
} // namespace

vpMorphViewAligner::vpMorphViewAligner() : m_cam(800, 800, 320, 240)
{
  for (unsigned int i = 0; i < 4; ++i)
    m_last.covariance[i][i] = std::numeric_limits<double>::infinity();
}

void vpMorphViewAligner::setCameraParameters(const vpCameraParameters &cam)
{
  m_cam = cam;
  if (!m_goalPx.empty())
    setGoal(vpMorphContour(m_goalPx));
}

void vpMorphViewAligner::setGoal(const vpMorphContour &goal)
{
  if (goal.empty() || goal.units() != vpMorphContour::PIXEL)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphViewAligner::setGoal: the goal must be a non-empty contour in pixels");
  m_goalPx = goal;
  m_goalN = goal.toNormalized(m_cam);
  m_fit.emplace(m_goalN);
  const vpMorphContour &o = m_goalN.outline();
  m_goalRegion = o.size() > kRegionPoints ? o.resampled(kRegionPoints) : o;
  m_tracker.reset();
  m_haveStart = false;
  m_last = vpMorphViewAlignment();
  for (unsigned int i = 0; i < 4; ++i)
    m_last.covariance[i][i] = std::numeric_limits<double>::infinity();
}

void vpMorphViewAligner::setStart(const vpMorphRigidTransform &currentToGoal)
{
  m_start = currentToGoal;
  m_startSigma = 0.0;
  m_haveStart = true;
}

void vpMorphViewAligner::reset()
{
  m_tracker.reset();
  m_haveStart = false;
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
  // The model test: runs of outliers longer than the noise makes (vpMorphOutlineFit::getOutsideShare()) are a part of
  // the view that the goal does not have; the side they lie on tells a part hidden (an occluder's edge inside the
  // goal) from a part bent out of it. Beyond the breakdown point, or a robust scale that no edge noise makes, the fit
  // does not stand for the view.
  a.overlapShare = overlapShare(T, currentN);
  if (a.overlapShare < kBreakdown || !(a.sigmaPx <= (measured ? outlineSigmaLimitPx() : polygonSigmaLimitPx())))
    a.model = vpMorphViewAlignment::UNEXPLAINED;
  else if (a.outsideShare + a.insideShare == 0.0)
    a.model = vpMorphViewAlignment::RIGID;
  else
    a.model = a.outsideShare > a.insideShare ? vpMorphViewAlignment::PART_BENT : vpMorphViewAlignment::PART_HIDDEN;
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
  return vpMorphRigidTransform::fitLeastSquares(currentN, m_goalN, corr, true, vpMorphRigidTransform::TUKEY, 30,
                                                normalisedPixels(0.5));
}

vpMorphViewAlignment vpMorphViewAligner::align(const vpMorphContour &current)
{
  if (m_goalPx.empty())
    throw vpMorphException(vpMorphException::badParameterError, "vpMorphViewAligner::align: no goal; call setGoal()");
  if (current.units() != vpMorphContour::PIXEL)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphViewAligner::align: the current contour must be in pixels");
  vpMorphViewAlignment result;
  for (unsigned int i = 0; i < 4; ++i)
    result.covariance[i][i] = std::numeric_limits<double>::infinity();
  try {
    if (current.empty())
      throw vpMorphException(vpMorphException::badContourError, "empty view");
    const vpMorphContour currentN = current.toNormalized(m_cam);
    if (m_method == PAPER) {
      vpMorphViewAlignment a;
      a.transform = correspondenceStart(currentN, a);
      a.model = vpMorphViewAlignment::RIGID;
      a.inlierShare = 1.0;
      a.fromCorrespondence = true;
      for (unsigned int i = 0; i < 4; ++i)
        a.covariance[i][i] = std::numeric_limits<double>::infinity();
      result = a;
    } else {
      vpMorphOutlineFit &fit = *m_fit;
      const bool measured = currentN.hasOutline() && m_goalN.hasOutline();
      fit.setMinimumSigma(normalisedPixels(measured ? outlineSigmaFloorPx() : polygonSigmaFloorPx()));
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
      if (!haveWarm || !warm.explained()) {
        vpMorphViewAlignment cold;
        const vpMorphRigidTransform T0 = correspondenceStart(currentN, cold);
        const vpMorphRigidTransform T = fit.search(currentN, T0);
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
  if (result.explained()) {
    m_start = result.transform;
    m_startSigma = result.sigmaPx / std::max(m_cam.get_px(), m_cam.get_py());
    m_haveStart = true;
  }
  m_last = result;
  return result;
}
