#include <visp3/morph/vpMorphPartRecognizer.h>

#include <cmath>

#include <visp3/morph/vpMorphException.h>

vpMorphPartRecognizer::vpMorphPartRecognizer(const vpMorphDatabase &db, unsigned int threads)
{
  if (db.empty())
    throw vpMorphException(vpMorphException::notFoundError, "vpMorphPartRecognizer: the database is empty");
  m_db = std::make_shared<const vpMorphDatabase>(db);
  if (db.distance().model() == vpMorphShapeDistance::RIGID)
    return;
  auto rigid = std::make_shared<vpMorphDatabase>(db);
  rigid->setDistance(vpMorphShapeDistance(vpMorphShapeDistance::RIGID));
  rigid->calibrate(threads);
  m_rigid = rigid;
}

vpMorphRecognition vpMorphPartRecognizer::recognize(const vpMorphContour &c, Stage *stage) const
{
  if (c.empty())
    throw vpMorphException(vpMorphException::badContourError, "vpMorphPartRecognizer::recognize: empty contour");
  if (stage)
    *stage = RIGID_STAGE;
  const vpMorphRecognition r = getRigidDatabase().recognize(c);
  if (r.accepted || r.ambiguous || !m_rigid)
    return r;
  if (stage)
    *stage = DISTANCE_STAGE;
  return m_db->recognize(c);
}

vpMorphPartRecognizer::Naming vpMorphPartRecognizer::namedAs(const vpMorphContour &c, std::size_t k) const
{
  if (k >= m_db->size())
    throw vpMorphException(vpMorphException::badParameterError, "vpMorphPartRecognizer::namedAs: no such template");
  if (c.empty())
    throw vpMorphException(vpMorphException::badContourError, "vpMorphPartRecognizer::namedAs: empty contour");
  const vpMorphRecognition r = getRigidDatabase().recognize(c);
  if (!r.accepted)
    return UNDECIDED;
  return r.index == k ? NAMED_TEMPLATE : NAMED_OTHER;
}

vpMorphRecognition vpMorphPartRecognizer::recognize(const std::vector<vpMorphContour> &candidates, std::size_t &chosen,
                                                    Stage *stage) const
{
  if (candidates.empty())
    throw vpMorphException(vpMorphException::badContourError, "vpMorphPartRecognizer::recognize: no candidate contour");
  vpMorphRecognition best;
  Stage bestStage = RIGID_STAGE;
  chosen = 0;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    Stage s;
    vpMorphRecognition r = recognize(candidates[k], &s);
    // An exact rigid fit outranks a deformation-tolerant one; within a stage, as vpMorphDatabase::recognize() ranks
    // candidates.
    const bool better = r.accepted && (!best.accepted || (s == RIGID_STAGE && bestStage != RIGID_STAGE) ||
                                       (s == bestStage && r.relativeDistance() < best.relativeDistance()));
    if (k == 0 || better) {
      best = std::move(r);
      bestStage = s;
      chosen = k;
    }
  }
  if (stage)
    *stage = bestStage;
  return best;
}
