/*
  \file vpMorphRigidShapeData.h
  \brief Internal to the morph module (not installed): what vpMorphRigidShape prepares, shared with vpMorphRigidCheck.
*/
#ifndef VP_MORPH_RIGID_SHAPE_DATA_H
#define VP_MORPH_RIGID_SHAPE_DATA_H

#include <algorithm>
#include <array>
#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphRigidShape.h>

#include "vpMorphInsideTest.h"
#include "vpMorphNearestEdge.h"

/*
  A contour prepared for alignment. The coarse stage (vpMorphRigidShape) uses the normalised frame (region centroid,
  size = square root of the region's area), the orientation histogram, the samples with their tangent directions
  bucketed by direction and, for a target, the signed distance grid to the polygon. The fine stage
  (vpMorphRigidCheck) uses the fine curve (the measured outline when there is one, else the polygon), its edges and
  samples along it.
*/
struct vpMorphRigidShapeData
{
  static constexpr int kBins = 72;                 // orientation histogram: 5 deg a bin
  static constexpr int kSamples = 64;              // coarse samples along the outline
  static constexpr int kGrid = 64;                 // signed distance grid cells a side
  static constexpr std::size_t kFineSamples = 256; // fine samples along the fine curve
  static constexpr int kLanes = 4;                 // points the coarse fit reads at once (vpMorphSimilarityFit)

  vpMorphContour contour, polygon; // as given; its polygon, counter-clockwise
  double cx = 0.0, cy = 0.0, size = 1.0;
  std::array<float, 2 * kBins> hist{}; // orientation histogram, twice over (for the circular correlation)
  std::vector<double> x, y;            // kSamples samples, normalised
  std::vector<int> bin;                // their tangent directions' bins
  // The samples that vote and are fitted when this shape is the input: every other one, on its own edges only when
  // the outline tells them and at least 4 are (vpMorphContour::ownEdge(): an occluder's edge belongs to no template)
  std::vector<int> inputs;
  // The inputs' samples and every other sample (the target side of the coarse cost), in float, zero-padded to a
  // multiple of kLanes: what the coarse fit reads (vpMorphSimilarityFit)
  std::vector<float> inputX, inputY, evenX, evenY;
  std::vector<int> bucketStart, bucket; // samples per direction bin (bucketStart[kBins] = kSamples)
  std::vector<float> voteX, voteY;      // the samples in bucket order, in shift-vote cells (vpMorphRigidShape)
  std::vector<float> grid;              // signed distance, normalised, kGrid x kGrid (empty: none)
  double lo = 0.0, step = 1.0;
  double invStep = 1.0;         // 1 / step
  bool measured;                // the fine curve is a measured outline
  vpMorphContour fine;          // the fine curve, counter-clockwise
  vpMorphNearestEdge fineEdges; // on it
  bool marked;                  // the fine curve tells its own edges (vpMorphContour::ownEdge())
  vpMorphInsideTest fineInside; // whether a point is inside it
  std::vector<double> fx, fy;   // kFineSamples samples along it, pixels
  std::vector<char> fown;       // per sample, whether it lies on the object's own edge (vpMorphContour::ownEdge())
  std::unique_ptr<const vpMorphNearestEdge> ownOnly;   // on its own edges, when some are not
  std::vector<vpMorphRigidShape::Symmetry> symmetries; // its turns onto itself, least cost first
  // The blur ladder (vpMorphRigidShape::atBlur()): rung k is the shape at blur k x blurRung(), empty when the blur
  // erases the part; filled on first use under the mutex, never erased (references to rungs stay valid).
  mutable std::mutex ladderMutex;
  mutable std::map<int, vpMorphRigidShape> ladder;

  explicit vpMorphRigidShapeData(const vpMorphContour &c)
    : contour(c), polygon(c.counterClockwise()), measured(c.hasOutline()), fine(c.outline().counterClockwise()),
      fineEdges(fine), marked(fine.hasOwnEdges()), fineInside(fine)
  {
    const vpMorphContour s = fine.resampled(kFineSamples);
    fx = s.xs();
    fy = s.ys();
    fown.resize(fx.size());
    for (std::size_t k = 0; k < fown.size(); ++k)
      fown[k] = s.ownEdge(k);
    std::vector<char> keep(fine.size());
    for (std::size_t k = 0; k < keep.size(); ++k)
      keep[k] = fine.ownEdge(k);
    if (marked && std::find(keep.begin(), keep.end(), 0) != keep.end())
      ownOnly.reset(new vpMorphNearestEdge(fine, keep));
  }

  // The fine curve's own edges (all of it when unmarked or all its own).
  const vpMorphNearestEdge &ownEdges() const { return ownOnly ? *ownOnly : fineEdges; }
};

#endif
