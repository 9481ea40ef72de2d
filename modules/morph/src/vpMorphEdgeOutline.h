/*
  \file vpMorphEdgeOutline.h
  \brief Internal to the morph module (not installed): an object's edge read on the grey levels about its region
  (vpMorphRegionMeasure): the gradient, the edge's level and slope, and the dense edge outline.
*/
#ifndef VP_MORPH_EDGE_OUTLINE_H
#define VP_MORPH_EDGE_OUTLINE_H

#include <vector>

#include <opencv2/core.hpp>

#include "vpMorphRegionMeasure.h"

namespace vpMorphEdgeOutline
{
// The gradient of g in grey levels per pixel (3x3 Sobel), for edgeProfile() and edgeOutline().
void gradient(const cv::Mat &g, cv::Mat &gx, cv::Mat &gy);

/*
  Grey level and slope (grey levels per pixel) of an edge at its gradient maxima: the medians over the
  band's pixels that are a maximum of the gradient magnitude along the gradient direction, each refined to the
  parabola's vertex; the level is then the one about which the profiles through those maxima are antisymmetric
  (antisymmetricLevel()): the peaks' own level is pulled by a clipped far side through the 3x3 derivative. False
  when too few maxima (under 16) are found. gx, gy: the gradient of g (see gradient()). With \e shading (a level
  across the image, g a box of it at \e tl), the edge's level varies along it as the shading does (a light that falls
  off scales the object's and the background's levels alike), and \e level is its value at the box's centre.
*/
bool edgeProfile(const cv::Mat &g, const cv::Mat &gx, const cv::Mat &gy, const cv::Mat &band, double minSlope,
                 double &level, double &slope, const vpMorphRegionMeasure::Level *shading = nullptr,
                 const cv::Point &tl = cv::Point());

/*
  The edge near each chain pixel, in image coordinates (chain pixel + box corner), one point per pixel.
  - Where the step is whole (fg to bg, not clipped): along the pixel's row, or its column when the edge is closer to
    horizontal, the edge is where the object's share of the 7 pixels about it ends, their weights (g - bg) /
    (fg - bg) (the levels at each pixel) summed from the object's end. Why: a pixel's grey level is the share of its
    area the object covers (then blurred, which keeps areas), so over a row the weights add up to the object's
    extent, averaged over the pixel's height: for a straight edge, exactly the edge at the row's centre, whatever its
    angle and blur. The level crossing of an interpolated profile is off by a pixel-phase-dependent tenth of a pixel
    on slanted edges.
  - Elsewhere (clipped levels, another edge within 3 px, the image border): along the gradient direction (3x3
    Sobel), the crossing nearest the pixel within 2 px of the level halfway between fg and bg there (\e clippedLevel
    when the step is not \e whole), the profile sampled bilinearly every quarter
    pixel and interpolated linearly.
  Pixels without a clear gradient (under the local contrast / 16 per pixel) or without a crossing are skipped.
  \e blur, when given, receives the edge's blur from the whole steps' profiles (left unchanged without any).
  \e own receives, per point, whether the edge from it to the next is the object's own edge: no chain pixel skipped
  between them (a bridge, where there is no edge), and each point's own (vpMorphOwnEdges() on \e object, the object mask
  of the box: beyond the edge's blur reach, 3 blur std, by a pixel and the patch's half diagonal).
*/
std::vector<cv::Point2d> edgeOutline(const cv::Mat &g, const cv::Mat &gx, const cv::Mat &gy,
                                     const std::vector<cv::Point> &chain, const cv::Point &tl,
                                     const vpMorphRegionMeasure::Level &fg, const vpMorphRegionMeasure::Level &bg,
                                     bool whole, double clippedLevel, const cv::Mat &object, std::vector<bool> &own,
                                     double *blur);
} // namespace vpMorphEdgeOutline

#endif
