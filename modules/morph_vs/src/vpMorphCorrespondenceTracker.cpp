#include <visp3/morph_vs/vpMorphCorrespondenceTracker.h>

#include "vpMorphParameterCheck.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <visp3/morph/vpMorphException.h>

vpMorphCorrespondenceTracker::vpMorphCorrespondenceTracker(const vpMorphMatcher &matcher) : m_matcher(matcher) {}

void vpMorphCorrespondenceTracker::setJumpFactor(double f)
{
  if (!std::isfinite(f) || f < 1.0) {
    std::ostringstream os;
    os << "vpMorphCorrespondenceTracker::setJumpFactor: the factor must be finite and >= 1, got " << f;
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
  m_jumpFactor = f;
}

void vpMorphCorrespondenceTracker::setWorkFloor(double w)
{
  vpMorphParameterCheck::nonNegative(w, "vpMorphCorrespondenceTracker::setWorkFloor", "the floor");
  m_workFloor = w;
}

void vpMorphCorrespondenceTracker::reset()
{
  m_corr = vpMorphCorrespondence();
  m_prevInput = vpMorphContour();
  m_prevTargetX.clear();
  m_prevTargetY.clear();
  m_source = NONE;
  m_prevWork = 0.0;
  m_margin = 1.0;
  m_lastOverride = false;
}

std::size_t vpMorphCorrespondenceTracker::carriedStart(const vpMorphContour &current) const
{
  const std::size_t a = m_corr.start().first;
  double pcx, pcy, ccx, ccy;
  m_prevInput.centroid(pcx, pcy);
  current.centroid(ccx, ccy);
  const double px = m_prevInput.x(a) - pcx + ccx, py = m_prevInput.y(a) - pcy + ccy;
  std::size_t best = 0;
  double bestD = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < current.size(); ++k) {
    const double d = std::hypot(current.x(k) - px, current.y(k) - py);
    if (d < bestD) {
      bestD = d;
      best = k;
    }
  }
  return best;
}

void vpMorphCorrespondenceTracker::measureMargin(const vpMorphContour &current, const vpMorphContour &target)
{
  const std::size_t n = target.size();
  const std::size_t guard = std::max<std::size_t>(1, n / 8);
  if (n < 2 * guard + 2) {
    m_margin = 1.0;
    return;
  }
  const std::size_t count = n - 2 * guard - 1; // starts farther than guard from the best one
  const std::size_t half = (count - 1) / 2;
  const std::size_t b = m_corr.start().second;
  const std::size_t centre = (b + guard + 1 + half) % n;
  const vpMorphCorrespondence alt = m_matcher.matchWindow(current, target, m_corr.start().first, centre, half);
  const double d = m_corr.work(), dAlt = alt.work();
  m_margin = dAlt > 1e-12 ? std::max(0.0, std::min(1.0, (dAlt - d) / dAlt)) : 0.0;
}

const vpMorphCorrespondence &vpMorphCorrespondenceTracker::update(const vpMorphContour &current,
                                                                  const vpMorphContour &target)
{
  if (current.empty() || target.empty())
    throw vpMorphException(vpMorphException::badContourError,
                           "vpMorphCorrespondenceTracker::update: empty current or target contour");
  const bool sameTarget = m_source != NONE && target.xs() == m_prevTargetX && target.ys() == m_prevTargetY;
  m_prevWork = m_source == NONE ? 0.0 : m_corr.work();
  bool done = false;
  bool jumpOnly = false;   // the window's best start is inside it, only its work jumped
  double windowWork = 0.0; // and that work
  if (sameTarget && !m_prevInput.empty()) {
    const std::size_t n = target.size();
    const std::size_t h = m_halfWidth > 0 ? m_halfWidth : std::max<std::size_t>(2, n / 8);
    const std::size_t a = carriedStart(current);
    const std::size_t bc = m_corr.start().second;
    vpMorphCorrespondence c = m_matcher.matchWindow(current, target, a, bc, h);
    const bool windowCoversAll = 2 * h + 1 >= n;
    const std::size_t b = c.start().second;
    const std::size_t off = std::min((b + n - bc) % n, (bc + n - b) % n);
    const bool inside = windowCoversAll || off < h;
    const bool noJump = c.work() <= m_jumpFactor * m_prevWork + m_workFloor;
    if (inside && noJump) {
      m_corr = std::move(c);
      m_source = TRACKED;
      ++m_trackedCount;
      done = true;
    } else {
      ++m_rejectedCount;
      jumpOnly = inside && !m_lastOverride;
      windowWork = c.work();
    }
  }
  if (!done) {
    double gain = 0.0;
    bool confirmed = false;
    vpMorphCorrespondence all; // the least work over all starts, when it was solved to confirm a jump
    if (jumpOnly && m_regionCheck) {
      // A real contour that gains or loses a vertex changes its work by far more than the jump factor while the
      // window still holds the best start. The least work over all starts, no lower than the window's, confirms it,
      // and the region check is not repeated: it was passed by the correspondence tracked here (see m_lastOverride),
      // which it confirms.
      all = m_matcher.match(current, target);
      confirmed = !(all.work() < windowWork * (1.0 - 1e-12));
      if (confirmed) {
        m_corr = std::move(all);
        ++m_confirmedJumps;
      }
    }
    if (!confirmed)
      m_corr = m_regionCheck ? m_matcher.matchOnRegions(current, target, 0.1, &gain, all.empty() ? nullptr : &all)
                             : m_matcher.match(current, target);
    m_lastOverride = gain > 0.0;
    m_source = FULL;
    ++m_fullCount;
    if (gain > 0.0) {
      // The starts far from this one include the minimal-work one: its work says nothing about this choice.
      m_margin = std::min(1.0, gain);
      ++m_regionOverrides;
    } else {
      measureMargin(current, target);
    }
  }
  m_prevInput = current;
  m_prevTargetX = target.xs();
  m_prevTargetY = target.ys();
  return m_corr;
}
