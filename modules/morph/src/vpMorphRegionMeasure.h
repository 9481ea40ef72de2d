/*
  \file vpMorphRegionMeasure.h
  \brief Internal to the morph module (not installed): the sub-pixel measures of an extracted region from the grey
  levels about its boundary (vpMorphContourExtractor).
*/
#ifndef VP_MORPH_REGION_MEASURE_H
#define VP_MORPH_REGION_MEASURE_H

#include <vector>

#include <opencv2/core.hpp>

namespace vpMorphRegionMeasure
{
// A grey level that varies affinely across the image: a + au u + av v at pixel (u, v) (column, row).
struct Level
{
  double a = 0.0, au = 0.0, av = 0.0;
  bool valid = false; // measured
  double at(double u, double v) const { return a + au * u + av * v; }
};

// One object region: its boundary chain (from the object mask) and, once measured, its sub-pixel measures.
struct Region
{
  std::vector<cv::Point> chain;
  double area;
  cv::Point first; // top-most, then left-most pixel: deterministic tie break
  // Grey-level (sub-pixel) area, centroid and central moments / area, in pixel-centre coordinates.
  double subArea = 0.0, cx = 0.0, cy = 0.0, mu20 = 0.0, mu11 = 0.0, mu02 = 0.0;
  // The measured edge, one point per chain pixel (image coordinates), when the levels were measured.
  std::vector<cv::Point2d> outline{};
  // Per outline point, whether the edge from it to the next is the object's own, not an occluder's edge nor a bridge.
  std::vector<bool> outlineOwn{};
  // The edge's blur (px): the std of the Gaussian that spreads a sharp step as the image does, the pixel's own area
  // included; 0 when not measured (no clear step, or a level clipped by the sensor).
  double edgeBlur = 0.0;
  Level fg{}, bg{}; // the object's and background's grey levels, when measured
};

/*
  Area and centroid of a region from its grey levels: pixels well inside count 1, pixels across the edge count
  their fraction of the way from the background level to the object level (both measured about the region, as affine
  functions of the position, so illumination, its fall-off across the view and contrast do not matter; the object's
  on its pixels 3 px deep, or for a part with none, a wire, from its edge). Unlike the pixel
  count or the boundary polygon, this moves continuously with the object and is unbiased by zero-mean noise (the weights
  are not clipped). The band is 3 px wide on each side, enough for the edge blur of a camera; other regions' pixels (\e
  bin, the object mask) are left out of it. The second-order moments come with it (the region's orientation, steadier
  than a fit over polygon vertices), the edge outline and its blur. Falls back to the binary region when the object and
  background levels cannot be told apart. \e levelsFrom, when given and measured, supplies both levels instead (a region
  that is not all object: a joined silhouette). With \e levelsOnly, only the levels are read (reg.fg, reg.bg): the
  largest piece of a joined silhouette lends its own.
*/
void measure(const cv::Mat &grey, const cv::Mat &bin, Region &reg, const Region *levelsFrom = nullptr,
             bool levelsOnly = false);
// How far beyond a region's bounding box measure() reads the image and the mask (pixels): the band and the ring beyond.
constexpr int kReach = 6;
} // namespace vpMorphRegionMeasure

#endif
