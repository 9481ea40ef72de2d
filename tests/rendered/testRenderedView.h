// Views shared by the rendered tests: an object's silhouette seen from a turned camera, aligned on a goal.
#ifndef TEST_RENDERED_VIEW_H
#define TEST_RENDERED_VIEW_H

#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpMath.h>
#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph_sim/vpMorphPlanarScene.h>
#include <visp3/morph_sim/vpMorphTagPoseEstimator.h>
#include <visp3/morph_vs/vpMorphViewAligner.h>

namespace vpMorphRenderedTest
{
//! The object seen from \e cMo, its silhouette extracted (the image's noise seeded by \e frame).
inline vpMorphContour seenFrom(const vpMorphPlanarScene &scene, const vpHomogeneousMatrix &cMo, unsigned int frame)
{
  vpImage<unsigned char> I;
  scene.render(cMo, I, frame);
  return vpMorphTagPoseEstimator::silhouette(I, scene.projectedTagCorners(cMo));
}

//! The object seen from the desired camera turned by \e deg about its optical axis, its silhouette extracted (the
//! image's noise seeded by the turn).
inline vpMorphContour view(const vpMorphPlanarScene &scene, const vpHomogeneousMatrix &cdMo, int deg)
{
  return seenFrom(scene, vpHomogeneousMatrix(0, 0, 0, 0, 0, vpMath::rad(deg)).inverse() * cdMo,
                  static_cast<unsigned int>(deg + 360));
}

//! \e current aligned on \e goal from no start, with \e scene's camera.
inline vpMorphViewAlignment alignCold(const vpMorphPlanarScene &scene, const vpMorphContour &goal,
                                      const vpMorphContour &current)
{
  vpMorphViewAligner aligner;
  aligner.setCameraParameters(scene.camera());
  aligner.setGoal(goal);
  return aligner.align(current);
}
} // namespace vpMorphRenderedTest

#endif
