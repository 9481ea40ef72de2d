/*
  \file vpMorphRegionJoin.h
  \brief Internal to the morph module (not installed): the pieces an occluder cut from an object joined into one
  outline (vpMorphContourExtractor::extractJoined()).
*/
#ifndef VP_MORPH_REGION_JOIN_H
#define VP_MORPH_REGION_JOIN_H

#include <vector>

#include "vpMorphRegionMeasure.h"

namespace vpMorphRegionJoin
{
/*
  Joins to \e seed the \e pieces whose boundary comes within \e maxGap pixels of the group (nearest first), each gap
  bridged by the convex hull of both boundaries' cut edges (vpMorphContourExtractor::extractJoined() says which
  pixels). \e joined receives the outer boundary of the group (unmeasured); false, and \e joined untouched, when no
  piece was near enough.
*/
bool join(const vpMorphRegionMeasure::Region &seed, std::vector<const vpMorphRegionMeasure::Region *> pieces,
          double maxGap, vpMorphRegionMeasure::Region &joined);
} // namespace vpMorphRegionJoin

#endif
