/*
  \file vpMorphOutlineShare.h
  \brief Internal to the morph module (not installed): how much of a target's outline an input shows once laid on it.
*/
#ifndef VP_MORPH_OUTLINE_SHARE_H
#define VP_MORPH_OUTLINE_SHARE_H

#include <algorithm>
#include <cmath>
#include <cstddef>

#include <visp3/core/vpException.h>
#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphCorrespondence.h>
#include <visp3/morph/vpMorphRigidTransform.h>

#include "vpMorphNearestEdge.h"

/*
  The share of 512 points spread evenly along the target's outline that lie within 1/256 of its perimeter of an input
  (2 px on a 500-px outline), and the similarity that lays the input so that it shows the most from a start: refined
  point to edge both ways, the input onto the target and the target onto the input. Both, because an occluder's edge
  belongs to the input alone and, where it runs a few pixels from a target edge, drags the first fit (a wedge under a
  card whose edge runs along its top: 0.32 of its outline shown), while the target's hidden stretch lies far from every
  edge of the input and is weighed out of the second (0.83). vpMorphDatabase::support() and
  vpMorphMatcher::matchOnRegions() (occluded views matched end for end) measure with it. It refers to the target: the
  target must outlive it.
*/
class vpMorphOutlineShare
{
public:
  explicit vpMorphOutlineShare(const vpMorphContour &target)
    : m_target(target), m_samples(target.resampled(512)), m_tolerance(target.perimeter() / 256.0)
  {
  }

  double tolerance() const { return m_tolerance; }

  /*
    The starts aligned() is given: the similarity fitted robustly (Tukey) to \e correspondence (input to target), and
    the same turned half a turn about the target's centroid, as the least work can match a nearly symmetric outline
    (a wedge) end for end. The robust fit's scale is floored at a quarter of the tolerance, as in aligned().
    \throw vpMorphException when the correspondence admits no fit.
  */
  vpMorphRigidTransform fitted(const vpMorphContour &input, const vpMorphCorrespondence &correspondence) const
  {
    return vpMorphRigidTransform::fitLeastSquares(input, m_target, correspondence, true, vpMorphRigidTransform::TUKEY,
                                                  30, 0.25 * m_tolerance);
  }
  vpMorphRigidTransform halfTurned(const vpMorphRigidTransform &T) const
  {
    double cx, cy;
    m_target.centroid(cx, cy);
    return vpMorphRigidTransform(M_PI, 0.0, 0.0, 1.0, cx, cy) * T;
  }

  //! Share of the target's samples within tolerance() of \e moved (NaN distances, an overflowed fit: not on it).
  double shownBy(const vpMorphContour &moved) const
  {
    const vpMorphNearestEdge onMoved(moved);
    std::size_t on = 0;
    for (std::size_t i = 0; i < m_samples.size(); ++i) {
      double mx, my;
      on += std::fabs(onMoved(m_samples.x(i), m_samples.y(i), mx, my)) <= m_tolerance ? 1 : 0;
    }
    return static_cast<double>(on) / static_cast<double>(m_samples.size());
  }

  /*
    The larger share of the two fits of \e input from \e start (input to target), the fit in \e fit if not null; 0 when
    both degenerate (a scale run to zero or beyond the doubles). The robust fits' scale is floored at a quarter of the
    tolerance: the vertices of both polygons lie on the pixel grid, and a scale of zero would keep only those that
    coincide.
  */
  double aligned(const vpMorphContour &input, const vpMorphRigidTransform &start,
                 vpMorphRigidTransform *fit = nullptr) const
  {
    const double minSigma = 0.25 * m_tolerance;
    double best = 0.0;
    for (const bool targetOntoInput : {false, true}) {
      try {
        const vpMorphRigidTransform F =
            targetOntoInput
                ? vpMorphRigidTransform::refineOnOutline(m_target, input, start.inverse(), true, minSigma).inverse()
                : vpMorphRigidTransform::refineOnOutline(input, m_target, start, true, minSigma);
        const double s = shownBy(F.apply(input));
        if (s > best) {
          best = s;
          if (fit)
            *fit = F;
        }
      } catch (const vpException &) {
        // that fit degenerated: the other may not have
      }
    }
    return best;
  }

private:
  const vpMorphContour &m_target;
  vpMorphContour m_samples;
  double m_tolerance;
};

#endif
