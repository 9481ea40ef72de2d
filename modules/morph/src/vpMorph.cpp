#include <visp3/morph/vpMorph.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include <visp3/morph/vpMorphException.h>

namespace
{
void checkContours(const vpMorphContour &input, const vpMorphContour &target)
{
  if (input.empty() || target.empty())
    throw vpMorphException(vpMorphException::badContourError,
                           std::string("vpMorph: the ") + (input.empty() ? "input" : "target") + " contour is empty");
  if (input.units() != target.units())
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorph: the input and target contours have different units (one in pixels, one "
                           "normalised): convert one with toPixels() or toNormalized() first");
}

vpMorphCorrespondence matchChecked(const vpMorphContour &input, const vpMorphContour &target,
                                   const vpMorphMatcher &matcher)
{
  checkContours(input, target);
  vpMorphMatcher m(matcher);
  return m.match(input, target);
}
} // namespace

vpMorph::vpMorph(const vpMorphContour &input, const vpMorphContour &target, Estimator estimator, bool withScale)
  : vpMorph(input, target, vpMorphMatcher(), estimator, withScale)
{
}

vpMorph::vpMorph(const vpMorphContour &input, const vpMorphContour &target, const vpMorphMatcher &matcher,
                 Estimator estimator, bool withScale)
  : vpMorph(input, target, matchChecked(input, target, matcher), estimator, withScale)
{
}

vpMorph::vpMorph(const vpMorphContour &input, const vpMorphContour &target, const vpMorphCorrespondence &correspondence,
                 Estimator estimator, bool withScale)
  : m_input(input), m_target(target), m_estimator(estimator), m_withScale(withScale), m_corr(correspondence)
{
  if (estimator == GIVEN)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorph: the GIVEN estimator needs the constructor that takes the rigid part");
  checkContours(input, target);
  vpMorphRigidTransform::checkCorrespondence(input, target, correspondence, "vpMorph");
  build();
}

vpMorph::vpMorph(const vpMorphContour &input, const vpMorphContour &target, const vpMorphCorrespondence &correspondence,
                 const vpMorphRigidTransform &rigid)
  : m_input(input), m_target(target), m_estimator(GIVEN), m_withScale(true), m_corr(correspondence), m_rigid(rigid)
{
  checkContours(input, target);
  vpMorphRigidTransform::checkCorrespondence(input, target, correspondence, "vpMorph");
  build();
}

void vpMorph::build()
{
  double cx, cy;
  m_input.centroid(cx, cy);
  switch (m_estimator) {
  case ELONGATION:
    m_rigid = vpMorphRigidTransform::fitElongation(m_input, m_target, m_corr, m_withScale);
    break;
  case LEAST_SQUARES:
    m_rigid = vpMorphRigidTransform::fitLeastSquares(m_input, m_target, m_corr, m_withScale);
    break;
  case NONE:
    m_rigid = vpMorphRigidTransform(0.0, 0.0, 0.0, 1.0, cx, cy);
    break;
  case GIVEN:
    break; // set by the constructor
  default: {
    std::ostringstream os;
    os << "vpMorph: unknown rigid estimator " << static_cast<int>(m_estimator);
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
  }
  try {
    m_rectified = m_estimator == NONE ? m_input : m_rigid.apply(m_input);
  } catch (const vpException &e) {
    throw vpMorphException(vpMorphException::badContourError,
                           "vpMorph: the rectified input is degenerate (" + e.getStringMessage() +
                               "): input and target differ in scale by too many orders of magnitude");
  }
}

vpMorphContour vpMorph::at(double t) const
{
  if (!std::isfinite(t) || t < 0.0 || t > 1.0) {
    std::ostringstream os;
    os << "vpMorph::at: t must be in [0, 1] (got " << t << ")";
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
  if (t == 0.0)
    return m_rectified;
  if (t == 1.0)
    return m_target;

  std::vector<std::pair<std::size_t, std::size_t>> pairs = m_corr.pairs();
  if (pairs.size() > 1 && pairs.back() == pairs.front())
    pairs.pop_back();
  std::vector<double> x, y;
  x.reserve(pairs.size());
  y.reserve(pairs.size());
  for (const auto &p : pairs) {
    const double xk = (1.0 - t) * m_rectified.x(p.first) + t * m_target.x(p.second);
    const double yk = (1.0 - t) * m_rectified.y(p.first) + t * m_target.y(p.second);
    // Coincident consecutive vertices (a vertex matched twice with no motion between) are one vertex.
    if (!x.empty() && x.back() == xk && y.back() == yk)
      continue;
    x.push_back(xk);
    y.push_back(yk);
  }
  while (x.size() > 1 && x.back() == x.front() && y.back() == y.front()) {
    x.pop_back();
    y.pop_back();
  }
  try {
    return vpMorphContour(x, y, m_target.units());
  } catch (const vpMorphException &e) {
    std::ostringstream os;
    os << "vpMorph::at(" << t << "): the interpolated contour is degenerate (" << e.getStringMessage()
       << "); the rigid part was probably not rectified";
    throw vpMorphException(vpMorphException::badContourError, os.str());
  }
}

std::size_t vpMorph::rigidFrameCount(std::size_t n) const
{
  if (n == 0 || m_estimator == NONE)
    return 0;
  return n - std::max<std::size_t>(1, n / 2);
}

std::vector<vpMorphContour> vpMorph::sequence(std::size_t n, bool longWay) const
{
  std::vector<vpMorphContour> frames;
  if (n == 0)
    return frames;
  frames.reserve(n);
  const std::size_t nr = rigidFrameCount(n), nd = n - nr;
  for (std::size_t k = 1; k <= nr; ++k) {
    if (k == nr) {
      frames.push_back(m_rectified);
      continue;
    }
    try {
      frames.push_back(m_rigid.interpolated(double(k) / double(nr), longWay).apply(m_input));
    } catch (const vpException &e) {
      std::ostringstream os;
      os << "vpMorph::sequence: rigid frame " << k << " of " << nr << " is degenerate (" << e.getStringMessage()
         << ")";
      throw vpMorphException(vpMorphException::badContourError, os.str());
    }
  }
  for (std::size_t k = 1; k <= nd; ++k)
    frames.push_back(at(double(k) / double(nd)));
  return frames;
}

std::vector<vpMorphContour> vpMorph::sequenceWithInput(std::size_t n) const
{
  std::vector<vpMorphContour> frames;
  frames.reserve(n + 1);
  frames.push_back(m_input);
  for (vpMorphContour &c : sequence(n))
    frames.push_back(std::move(c));
  return frames;
}
