/*
  \file vpMorphBuckets.h
  \brief Internal to the morph module (not installed): items laid out bucket by bucket, for the edge grids.
*/
#ifndef VP_MORPH_BUCKETS_H
#define VP_MORPH_BUCKETS_H

#include <cstddef>
#include <vector>

/*
  Lays items out bucket by bucket (a counting sort): \e forEach(f) calls f(bucket, item) for every bucket each item
  belongs to, the items in increasing order, twice (to count, then to fill). Afterwards the items of bucket b are
  entries[first[b]] to entries[first[b + 1] - 1], in increasing order. \e cursor is the fill's cursor per bucket, given
  by the caller so that a structure rebuilt at every step keeps its storage. Shared by the grids of vpMorphNearestEdge,
  vpMorphOverlapPolygon and vpMorphInsideTest.
*/
template <class Entry, class ForEach>
void vpMorphFillBuckets(std::size_t buckets, ForEach &&forEach, std::vector<std::size_t> &first,
                        std::vector<Entry> &entries, std::vector<std::size_t> &cursor)
{
  first.assign(buckets + 1, 0);
  forEach([&](std::size_t b, std::size_t) { ++first[b + 1]; });
  for (std::size_t b = 1; b < first.size(); ++b)
    first[b] += first[b - 1];
  entries.resize(first.back());
  cursor.assign(first.begin(), first.end() - 1);
  forEach([&](std::size_t b, std::size_t k) { entries[cursor[b]++] = static_cast<Entry>(k); });
}

#endif
