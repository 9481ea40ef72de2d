/*
  \file vpMorphRegionCheck.h
  \brief Internal to the morph_vs module (not installed): how the current region compares with the goal's.
*/
#ifndef VP_MORPH_REGION_CHECK_H
#define VP_MORPH_REGION_CHECK_H

#include <cmath>
#include <cstddef>

#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphRigidTransform.h>

//! The tests that vpServoMorph and vpFeatureMorph make of the current region against the goal's.
class vpMorphRegionCheck
{
public:
  //! Change of the regions' similarity invariants above which they are not alike (vpServoMorph's default too).
  static constexpr double kRegionMismatch = 0.02;
  //! Share of the current region outside the goal's, once laid on it, above which the view is deformed (an occluder
  //! only hides; the edge outlines' noise leaves under 0.6 % out on the noise set, bends of 10-15 deg 3-14 %).
  static constexpr double kDeformedOutside = 0.02;
  //! Points of the resampled outlines the overlap is measured on (about 5 pixels apart: 0.025 ms an evaluation).
  static constexpr std::size_t kOverlapPoints = 128;
  /*!
    The largest undeformed part of a deformed view: edges within this distance (pixels) of the goal's, over at least
    this share of the outline, searched every kRigidPartPeriod periods (milliseconds) and followed in between. The
    edges of a curved part measured in two images differ by 0.1-0.2 px with the pixel phase (a bow is a polygon of short
    sides): at 0.15 px, a key's bow fell apart into stretches that a straight edge outran.
  */
  static constexpr double kRigidPartTolerancePx = 0.25, kRigidPartMinShare = 0.1;
  static constexpr unsigned int kRigidPartPeriod = 8;

  /*
    Whether two contours show one region seen twice (up to a similarity), so that the areas and centroids of their
    regions can stand for the pose: not so when part of the object is hidden or it is deformed. With measured
    regions, compared by two similarity invariants of their second-order moments (spread over area, and
    eccentricity): noise and blur move them by under 1 %, a card hiding 5-20 % of a tool by 5-33 % (measured on the
    bench sets). A polygon-fitted scale is not used there: on a thin-handled tool it strays 2-3 % from the region's (a
    noisy first frame was judged occluded and vpServoMorph stopped 1.5 mm deep). A region on one side only is not
    alike: an extracted contour without its region is an outline joined across an occluder's cut, whose polygon area
    and centroid carry the bridge (measured: an occluded screwdriver settling 8.2 mm off, a key re-planning until the
    limit). Without regions on either side, the polygons' area ratio against the fitted scale \e fittedScale.
  */
  static bool alike(const vpMorphContour &goal, const vpMorphContour &current, double fittedScale, double tolerance)
  {
    if (goal.hasRegion() && current.hasRegion()) {
      double sg, eg, sc, ec;
      invariants(goal, sg, eg);
      invariants(current, sc, ec);
      return sg > 0.0 && std::fabs(sc / sg - 1.0) <= tolerance && std::fabs(ec - eg) <= tolerance;
    }
    if (goal.hasRegion() != current.hasRegion())
      return false;
    return std::fabs(std::sqrt(goal.area() / current.area()) / fittedScale - 1.0) <= tolerance;
  }

  /*
    Share of \e view's area that lies outside \e goal once moved by \e F: an occluder only hides, a bend or an
    opening sticks out. 1 for a fit run to a point (0 / 0 would make it win every comparison).
  */
  static double outsideShare(const vpMorphRigidTransform &F, const vpMorphContour &view, const vpMorphContour &goal)
  {
    const vpMorphContour laid = F.apply(view);
    const double a = laid.area();
    return a > 0.0 && std::isfinite(a) ? 1.0 - laid.overlapArea(goal) / a : 1.0;
  }

private:
  static void invariants(const vpMorphContour &c, double &spread, double &eccentricity)
  {
    double mu20, mu11, mu02;
    c.regionMoments(mu20, mu11, mu02);
    const double tr = mu20 + mu02;
    spread = tr / c.regionArea();
    eccentricity = tr > 0.0 ? std::hypot(mu20 - mu02, 2.0 * mu11) / tr : 0.0;
  }
};

#endif
