/*
  \file vpMorphOwnEdges.h
  \brief Internal to the morph module (not installed): which points of a measured edge outline are the object's own
  edge, and which an occluder's (vpMorphRegionMeasure's edge outline, vpMorphContour::ownEdge()).
*/
#ifndef VP_MORPH_OWN_EDGES_H
#define VP_MORPH_OWN_EDGES_H

#include <vector>

#include <opencv2/core.hpp>

/*
  Whether each edge point \e points[k] (image coordinates; \e outward[k] its unit normal away from the object) is the
  object's own edge: the background lies beyond it, or the object itself (a groove, another limb). Beyond is the mean
  of the 3 x 3 pixels centred \e beyond past the point. Where they come within the edge's blur reach (\e reach) of an
  object pixel (\e object, the object mask of the box at \e tl), it is the object's: an own edge, not measured. Else
  it is compared with the background's level there, an affine function of the position (a light's fall-off) fitted to
  the measured means within 4 sigma (1.4826 MAD of the side that deviates less, at least half a grey level) of their
  median, then of that fit: the background is what most of an object's outline borders, so an occluder's few means
  do not pull it. A mean within 4 sigma of the fit is the background's; one off it, an occluder's. Points whose patch
  leaves the image are not own edges (the image's border cuts the object there). \e g and \e object are views of one
  box (at \e tl) of the image and of its object mask: when they are cut from those images (cv::Mat regions of
  interest), the patches and the object pixels near them are read past the box, so that the box's margin need not
  cover the patches (only the image's border cuts them).
*/
std::vector<bool> vpMorphOwnEdges(const cv::Mat &g, const cv::Mat &object, const cv::Point &tl,
                                  const std::vector<cv::Point2d> &points, const std::vector<cv::Point2d> &outward,
                                  double beyond, double reach);

#endif
