#include "vpMorphRegionJoin.h"

#include <algorithm>
#include <climits>
#include <cmath>

#include <opencv2/imgproc.hpp>

using vpMorphRegionMeasure::Region;

namespace
{
// Closest pair of pixels between two chains (brute force: chains are a few thousand pixels at most).
double closestPair(const std::vector<cv::Point> &a, const std::vector<cv::Point> &b, cv::Point &pa, cv::Point &pb)
{
  long best = LONG_MAX;
  for (const cv::Point &p : a)
    for (const cv::Point &q : b) {
      const long dx = p.x - q.x, dy = p.y - q.y, d2 = dx * dx + dy * dy;
      if (d2 < best) {
        best = d2;
        pa = p;
        pb = q;
      }
    }
  return best == LONG_MAX ? INFINITY : std::sqrt(double(best));
}

// Distance between two rectangles (0 when they overlap): a lower bound of the distance between what they hold.
double rectGap(const cv::Rect &a, const cv::Rect &b)
{
  const int dx = std::max({0, b.x - (a.x + a.width - 1), a.x - (b.x + b.width - 1)});
  const int dy = std::max({0, b.y - (a.y + a.height - 1), a.y - (b.y + b.height - 1)});
  return std::hypot(double(dx), double(dy));
}

// The pixels of a chain within r of a point.
void near(const std::vector<cv::Point> &chain, const cv::Point &c, double r, std::vector<cv::Point> &out)
{
  for (const cv::Point &p : chain)
    if (std::abs(p.x - c.x) <= r && std::abs(p.y - c.y) <= r && std::hypot(double(p.x - c.x), double(p.y - c.y)) <= r)
      out.push_back(p);
}

// The pixels of a chain within r of c that lie within \e reach of the other chain.
void cutEdge(const std::vector<cv::Point> &chain, const cv::Point &c, double r, const std::vector<cv::Point> &other,
             double reach, std::vector<cv::Point> &out)
{
  std::vector<cv::Point> candidates, others;
  near(chain, c, r, candidates);
  if (candidates.empty())
    return;
  // Only the other chain's pixels within r + reach of c can be within reach of a candidate: a few dozen instead of
  // the whole chain for each candidate (the same pixels result).
  near(other, c, r + reach, others);
  const double reach2 = reach * reach;
  for (const cv::Point &p : candidates)
    for (const cv::Point &q : others) {
      const double dx = p.x - q.x, dy = p.y - q.y;
      if (dx * dx + dy * dy <= reach2) {
        out.push_back(p);
        break;
      }
    }
}
} // namespace

bool vpMorphRegionJoin::join(const Region &seed, std::vector<const Region *> pieces, double maxGap, Region &joined)
{
  // The join is drawn over the pieces' box only (a pixel of background all round), not the whole image.
  cv::Rect all = cv::boundingRect(seed.chain);
  for (const Region *p : pieces)
    all |= cv::boundingRect(p->chain);
  const cv::Point offset = cv::Point(1, 1) - all.tl();
  cv::Mat drawn = cv::Mat::zeros(all.height + 2, all.width + 2, CV_8UC1);
  auto fill = [&drawn, &offset](const std::vector<cv::Point> &poly, bool convex) {
    std::vector<cv::Point> shifted(poly);
    for (cv::Point &p : shifted)
      p += offset;
    if (convex)
      cv::fillConvexPoly(drawn, shifted, cv::Scalar(255), cv::LINE_8);
    else
      cv::drawContours(drawn, std::vector<std::vector<cv::Point> >{shifted}, 0, cv::Scalar(255), cv::FILLED);
  };
  fill(seed.chain, false);
  // Nearest piece first, each gap bridged by the convex hull of both sides' pixels near it (within 1.5 gaps): a
  // cut straight across a limb is closed by the limb's own width, a bite out of a side is not filled beyond it.
  // Each piece keeps its nearest link to the group, updated as pieces join (one chain-to-chain search per pair at
  // most, none for pairs whose boxes are already farther apart: a noisy frame can hold many pieces).
  struct Link
  {
    double d = INFINITY;
    const Region *g = nullptr;
    cv::Point pg, pp;
  };
  std::vector<Link> links(pieces.size());
  std::vector<cv::Rect> boxes;
  for (const Region *p : pieces)
    boxes.push_back(cv::boundingRect(p->chain));
  auto linkTo = [&](const Region *g) {
    const cv::Rect gb = cv::boundingRect(g->chain);
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      if (rectGap(gb, boxes[k]) > std::min(links[k].d, maxGap))
        continue;
      cv::Point a, b;
      const double d = closestPair(g->chain, pieces[k]->chain, a, b);
      if (d < links[k].d)
        links[k] = Link{d, g, a, b};
    }
  };
  linkTo(&seed);
  bool any = false;
  while (!pieces.empty()) {
    std::size_t bestPiece = 0;
    for (std::size_t k = 1; k < pieces.size(); ++k)
      if (links[k].d < links[bestPiece].d)
        bestPiece = k;
    const Link best = links[bestPiece];
    if (!(best.d <= maxGap))
      break;
    // Of the pixels near the gap, those about as close to the other side as the closest pair: the two cut edges
    // (a card's edges are parallel, so each lies at the gap's width from the other) and the start of the limb's
    // sides. Not the rest of a bow or a head within 1.5 gaps of a long cut, whose hull would fill a triangle
    // between them (a key cut along its shaft joined into a blob).
    const double r = std::max(1.5 * best.d, 3.0), slack = std::max(2.0, 0.25 * best.d);
    std::vector<cv::Point> bridge, hull;
    cutEdge(best.g->chain, best.pg, r, pieces[bestPiece]->chain, best.d + slack, bridge);
    cutEdge(pieces[bestPiece]->chain, best.pp, r, best.g->chain, best.d + slack, bridge);
    cv::convexHull(bridge, hull);
    fill(pieces[bestPiece]->chain, false);
    fill(hull, true);
    const Region *joinedPiece = pieces[bestPiece];
    pieces.erase(pieces.begin() + static_cast<std::ptrdiff_t>(bestPiece));
    links.erase(links.begin() + static_cast<std::ptrdiff_t>(bestPiece));
    boxes.erase(boxes.begin() + static_cast<std::ptrdiff_t>(bestPiece));
    linkTo(joinedPiece);
    any = true;
  }
  if (!any)
    return false;
  std::vector<std::vector<cv::Point> > contours;
  cv::findContours(drawn, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  const auto it = std::max_element(contours.begin(), contours.end(), [](const auto &a, const auto &b) {
    return cv::contourArea(a) < cv::contourArea(b);
  });
  joined = Region{*it, cv::contourArea(*it), cv::Point()};
  for (cv::Point &p : joined.chain)
    p -= offset;
  return true;
}
