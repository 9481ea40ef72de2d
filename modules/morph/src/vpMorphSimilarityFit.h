/*
  \file vpMorphSimilarityFit.h
  \brief Internal to the morph module (not installed): a similarity between two prepared shapes in their normalised
  frames, its cost and its Gauss-Newton refinement on the target's signed distance grid (vpMorphRigidShape's coarse
  stage).
*/
#ifndef VP_MORPH_SIMILARITY_FIT_H
#define VP_MORPH_SIMILARITY_FIT_H

#include <visp3/morph/vpMorphRigidTransform.h>

struct vpMorphRigidShapeData;

namespace vpMorphSimilarityFit
{
// A similarity in the shapes' normalised frames: X = a x - b y + tx, Y = b x + a y + ty.
struct Sim
{
  double a = 1.0, b = 0.0, tx = 0.0, ty = 0.0;
};

// s after t: X = s(t(x)).
Sim compose(const Sim &s, const Sim &t);

// \e T (input pixels to target pixels) in the normalised frames of \e in and \e t, and back.
Sim toSim(const vpMorphRigidShapeData &in, const vpMorphRigidShapeData &t, const vpMorphRigidTransform &T);
vpMorphRigidTransform toPixels(const vpMorphRigidShapeData &in, const vpMorphRigidShapeData &t, const Sim &s);

// Mean distance, truncated at tau and divided by it, of the input's fitted samples (vpMorphRigidShapeData::inputs)
// to the target's grid (0: all on its outline, 1: none within tau or off the grid).
double inputCost(const vpMorphRigidShapeData &in, const vpMorphRigidShapeData &t, const Sim &s, double tau);

// The same of the target's samples (every other one) mapped back by \e s onto the input's grid, in target sizes.
double targetCost(const vpMorphRigidShapeData &in, const vpMorphRigidShapeData &t, const Sim &s, double tau);

/*
  Up to \e iterations Gauss-Newton steps from \e s on the target's grid: the input's fitted samples within tau pull
  their point onto the zero level. Stops early when fewer than 4 samples are within (no similarity is fixed), the
  system is singular, or a step moves the parameters by less than a ten-thousandth of a size.
*/
Sim refine(const vpMorphRigidShapeData &in, const vpMorphRigidShapeData &t, Sim s, double tau, int iterations);
} // namespace vpMorphSimilarityFit

#endif
