/*!
  \file vpMorphPlanarSceneShared.h
  \brief Internal: what the parts of vpMorphPlanarScene's implementation share (the tag texture's cell, points of the
  plane, the checks of parameters and poses).
*/
#ifndef VP_MORPH_PLANAR_SCENE_SHARED_H
#define VP_MORPH_PLANAR_SCENE_SHARED_H

#include <cmath>
#include <string>

#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpPoint.h>
#include <visp3/morph/vpMorphException.h>

namespace vpMorphPlanarSceneShared
{
const unsigned int kTagCell = 10; // tag texture: 10 x 10 cells of 10 px

inline void badParameter(const std::string &msg) { throw vpMorphException(vpMorphException::badParameterError, msg); }

inline bool isFinite(double v) { return std::isfinite(v); }

inline vpPoint planePoint(double x, double y)
{
  vpPoint p;
  p.setWorldCoordinates(x, y, 0.0);
  return p;
}

inline bool finitePose(const vpHomogeneousMatrix &M)
{
  for (unsigned int i = 0; i < 4; ++i)
    for (unsigned int j = 0; j < 4; ++j)
      if (!std::isfinite(M[i][j]))
        return false;
  return M.isAnHomogeneousMatrix();
}
} // namespace vpMorphPlanarSceneShared

#endif
