// vpMorphPlanarScene's layout: where the tag, the occluder and the distractors lie on the plane.
#include <visp3/morph_sim/vpMorphPlanarScene.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <visp3/core/vpMeterPixelConversion.h>
#include <visp3/morph_sim/vpMorphTagTexture.h>

#include "vpMorphPlanarSceneShared.h"

using namespace vpMorphPlanarSceneShared;

namespace
{
// Dense samples (every step metres) along the closed polygon (x, y).
void densify(const std::vector<double> &x, const std::vector<double> &y, double step, std::vector<double> &sx,
             std::vector<double> &sy)
{
  sx.clear();
  sy.clear();
  const size_t n = x.size();
  for (size_t k = 0; k < n; ++k) {
    const size_t l = (k + 1) % n;
    const double dx = x[l] - x[k], dy = y[l] - y[k];
    const int m = std::max(1, static_cast<int>(std::ceil(std::hypot(dx, dy) / step)));
    for (int i = 0; i < m; ++i) {
      sx.push_back(x[k] + dx * i / m);
      sy.push_back(y[k] + dy * i / m);
    }
  }
}

// Even-odd point-in-polygon test.
bool inside(const std::vector<double> &x, const std::vector<double> &y, double px, double py)
{
  bool in = false;
  for (size_t i = 0, j = x.size() - 1; i < x.size(); j = i++)
    if ((y[i] > py) != (y[j] > py) && px < (x[j] - x[i]) * (py - y[i]) / (y[j] - y[i]) + x[i])
      in = !in;
  return in;
}

struct TagCandidate
{
  double x, y, distance; // centre in the object frame, its distance to the object's centre (m)
};

/*!
  For each of \e directions directions around the object's centre (ox, oy), the nearest centre (1 mm steps) at which a
  tag texture of half side \e half lies 1 cm clear of the outline (x, y) (no outline sample within 1 cm of the
  square, the centre outside the object); directions where none is found within reach give none.
*/
std::vector<TagCandidate> tagCandidates(const std::vector<double> &x, const std::vector<double> &y, double ox,
                                        double oy, double radius, double half, int directions)
{
  std::vector<double> sx, sy;
  densify(x, y, 0.001, sx, sy);
  std::vector<TagCandidate> out;
  for (int k = 0; k < directions; ++k) {
    const double a = k * 2.0 * M_PI / directions;
    for (double d = 0.0; d < radius + 3 * half + 0.02; d += 0.001) {
      const double tx = ox + d * std::cos(a), ty = oy + d * std::sin(a);
      bool clear = !inside(x, y, tx, ty);
      for (size_t i = 0; i < sx.size() && clear; ++i)
        clear = std::max(std::fabs(sx[i] - tx), std::fabs(sy[i] - ty)) > half + 0.01;
      if (clear) {
        out.push_back({tx, ty, d});
        break;
      }
    }
  }
  return out;
}

} // namespace

bool vpMorphPlanarScene::placeTagInView(const vpHomogeneousMatrix &cMo, const std::vector<double> &tagSizes,
                                        double margin)
{
  if (!finitePose(cMo) || !isFinite(margin))
    badParameter("vpMorphPlanarScene::placeTagInView: invalid cMo or margin");
  for (double size : tagSizes)
    if (!isFinite(size) || size <= 0.0)
      badParameter("vpMorphPlanarScene::placeTagInView: tag sizes must be finite and > 0");
  std::vector<double> x, y;
  double radius = 0.0;
  for (const vpPoint &p : objectContour3D()) {
    x.push_back(p.get_oX());
    y.push_back(p.get_oY());
    radius = std::max(radius, std::hypot(p.get_oX() - m_objX, p.get_oY() - m_objY));
  }
  for (double size : tagSizes) {
    const double half = vpMorphTagTexture::textureSideForTagSize(size, kTagCell) / 2;
    const TagCandidate *best = nullptr;
    const std::vector<TagCandidate> candidates = tagCandidates(x, y, m_objX, m_objY, radius, half, 24);
    for (const TagCandidate &c : candidates) {
      const std::vector<vpPoint> square = {planePoint(c.x - half, c.y - half), planePoint(c.x + half, c.y - half),
                                           planePoint(c.x + half, c.y + half), planePoint(c.x - half, c.y + half)};
      bool in = true;
      for (vpPoint p : square) {
        p.track(cMo);
        double u = 0.0, v = 0.0;
        vpMeterPixelConversion::convertPoint(m_cam, p.get_x(), p.get_y(), u, v);
        in = in && p.get_Z() > 0.0 && u >= margin && v >= margin && u <= m_width - 1.0 - margin &&
             v <= m_height - 1.0 - margin;
      }
      if (in && (!best || c.distance < best->distance - 1e-9))
        best = &c;
    }
    if (best) {
      m_tagSize = size;
      m_tagAuto = false;
      m_tagX = best->x;
      m_tagY = best->y;
      updateLayout();
      return true;
    }
  }
  return false;
}
double vpMorphPlanarScene::occludedShare() const { return m_occludedShare; }
std::vector<vpPoint> vpMorphPlanarScene::occluderCorners3D() const { return m_occluder; }
std::vector<std::vector<vpPoint>> vpMorphPlanarScene::distractorCorners3D() const { return m_distractors; }

void vpMorphPlanarScene::updateLayout()
{
  const std::vector<vpPoint> P = objectContour3D();
  std::vector<double> x, y;
  double radius = 0.0; // of the outline about its centroid
  for (const vpPoint &p : P) {
    x.push_back(p.get_oX());
    y.push_back(p.get_oY());
    radius = std::max(radius, std::hypot(p.get_oX() - m_objX, p.get_oY() - m_objY));
  }
  const double tagHalf = vpMorphTagTexture::textureSideForTagSize(m_tagSize, kTagCell) / 2; // with quiet zone
  if (m_tagAuto) {
    // The nearest of 8 directions (the first found among equals).
    double best = 1e9;
    for (const TagCandidate &c : tagCandidates(x, y, m_objX, m_objY, radius, tagHalf, 8))
      if (c.distance < best - 1e-9) {
        best = c.distance;
        m_tagX = c.x;
        m_tagY = c.y;
      }
  }

  // Occluder: a square centred on the outline point at the requested arc length, grown by bisection until the
  // requested share of the densely sampled outline lies inside it.
  m_occluder.clear();
  m_occludedShare = 0.0;
  std::vector<double> sx, sy;
  densify(x, y, 0.0005, sx, sy);
  if (m_faults.occludedShare > 0.0) {
    const size_t c = std::min(sx.size() - 1, static_cast<size_t>(m_faults.occluderPosition * sx.size()));
    auto share = [&](double h) {
      size_t in = 0;
      for (size_t i = 0; i < sx.size(); ++i)
        in += (std::fabs(sx[i] - sx[c]) <= h && std::fabs(sy[i] - sy[c]) <= h) ? 1 : 0;
      return static_cast<double>(in) / sx.size();
    };
    double lo = 0.0, hi = 2.5 * radius;
    for (int it = 0; it < 40; ++it) {
      const double mid = 0.5 * (lo + hi);
      (share(mid) < m_faults.occludedShare ? lo : hi) = mid;
    }
    const double h = hi;
    m_occludedShare = share(h);
    m_occluder = {planePoint(sx[c] - h, sy[c] - h), planePoint(sx[c] + h, sy[c] - h), planePoint(sx[c] + h, sy[c] + h),
                  planePoint(sx[c] - h, sy[c] + h)};
  }

  // Distractors: small dark rectangles placed by the seeded generator, clear of the object and of the tag.
  m_distractors.clear();
  std::mt19937 rng(m_faults.seed * 7919u + 17u);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const double keepObject = radius + 0.015, keepTag = tagHalf * std::sqrt(2.0) + 0.01;
  for (unsigned int k = 0, tries = 0; k < m_faults.distractors && tries < 10000; ++tries) {
    const double L = 0.015 + 0.02 * U(rng), W = 0.006 + 0.01 * U(rng), a = 2 * M_PI * U(rng);
    const double cx = m_objX + (U(rng) - 0.5) * 0.36, cy = m_objY + (U(rng) - 0.5) * 0.26;
    const double r = 0.5 * std::hypot(L, W);
    if (std::hypot(cx - m_objX, cy - m_objY) < keepObject + r || std::hypot(cx - m_tagX, cy - m_tagY) < keepTag + r)
      continue;
    bool overlaps = false;
    for (const auto &d : m_distractors) {
      const double dx = 0.5 * (d[0].get_oX() + d[2].get_oX()), dy = 0.5 * (d[0].get_oY() + d[2].get_oY());
      overlaps = overlaps || std::hypot(cx - dx, cy - dy) < r + 0.03;
    }
    if (overlaps)
      continue;
    const double c = std::cos(a), s = std::sin(a);
    auto corner = [&](double u, double v) { return planePoint(cx + c * u - s * v, cy + s * u + c * v); };
    m_distractors.push_back(
        {corner(-L / 2, -W / 2), corner(L / 2, -W / 2), corner(L / 2, W / 2), corner(-L / 2, W / 2)});
    ++k;
  }
  if (m_faults.largeDistractorArea > 0.0) {
    const double L = std::sqrt(m_faults.largeDistractorArea * m_faults.largeDistractorAspect);
    const double W = m_faults.largeDistractorArea / L;
    const double c = std::cos(m_faults.largeDistractorAngle), s = std::sin(m_faults.largeDistractorAngle);
    const double cx = m_faults.largeDistractorX, cy = m_faults.largeDistractorY;
    auto corner = [&](double u, double v) { return planePoint(cx + c * u - s * v, cy + s * u + c * v); };
    m_distractors.push_back(
        {corner(-L / 2, -W / 2), corner(L / 2, -W / 2), corner(L / 2, W / 2), corner(-L / 2, W / 2)});
  }
}

