//! \example tutorial-morph-recognition.cpp
//! Recognition by least morph work: build a template database from images, recognise a rotated, noisy and
//! partly occluded view of a known object and a view with a notch bitten out of it, and reject an object that is
//! not in the database. With a display, shows each view with its contour (red) and the template recognised laid on it
//! (green; orange when rejected). Usage: [OBJECTS_DIR] [-c] [-d] [--save-display FILE].
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpImage.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorph.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphDatabase.h>
#include <visp3/morph/vpMorphPartRecognizer.h>

#include "tutorial-display.h"

namespace
{
// A new view of an image: rotated by theta (radians) about the image centre and shifted by (tx, ty) pixels;
// what comes in from outside the image is white background.
vpImage<unsigned char> newView(const vpImage<unsigned char> &I, double theta, double tx, double ty)
{
  vpImage<unsigned char> V(I.getHeight(), I.getWidth(), 255);
  const double cu = I.getWidth() / 2.0, cv = I.getHeight() / 2.0, c = std::cos(theta), s = std::sin(theta);
  for (unsigned int v = 0; v < V.getHeight(); ++v)
    for (unsigned int u = 0; u < V.getWidth(); ++u) {
      // Inverse map, nearest neighbour: where pixel (u, v) of the view comes from in I.
      const double x = u - cu - tx, y = v - cv - ty;
      const long su = std::lround(cu + c * x + s * y), sv = std::lround(cv - s * x + c * y);
      if (su >= 0 && sv >= 0 && su < static_cast<long>(I.getWidth()) && sv < static_cast<long>(I.getHeight()))
        V[v][u] = I[static_cast<unsigned int>(sv)][static_cast<unsigned int>(su)];
    }
  return V;
}

/*!
  A window on \e I (when a display is available) with the view's contour \e c (red), the template \e r recognised
  laid on it by the morph's rigid part (green if accepted, orange if rejected), and the verdict as a caption.
  Registers what the display test checks there.
*/
void show(tutorial::Viewer &viewer, vpImage<unsigned char> &I, int x, int y, const std::string &tag,
          const vpMorphContour &c, const vpMorphDatabase &db, const vpMorphRecognition &r)
{
  if (!viewer.open(I, x, y, tag + ": contour (red), template laid on it (green: accepted, orange: rejected)", tag))
    return;
  char line[160];
  std::snprintf(line, sizeof line, "%s %s: distance %.3f, threshold %.3f",
                r.accepted ? "recognised as" : "rejected, closest is", db[r.index].name().c_str(), r.distance,
                r.threshold);
  const std::vector<std::string> caption = {tag, line};
  const vpColor verdict = r.accepted ? vpColor::green : vpColor::orange;
  const vpMorphContour laid = vpMorph(db[r.index].contour(), c).rectified();
  vpDisplay::display(I);
  vpDisplay::displayPolygon(I, laid.points(), verdict, 4);
  vpDisplay::displayPolygon(I, c.points(), vpColor::red, 1);
  tutorial::Viewer::caption(I, caption);
  vpDisplay::flush(I);
  if (r.accepted)
    viewer.expectContour(tag, "template laid on the view", laid.points(), vpColor::green);
  viewer.expectText(tag, "verdict", tutorial::Viewer::captionBand(caption), vpColor::white, caption);
}
} // namespace

int main(int argc, char **argv)
{
  std::vector<std::string> args;
  tutorial::Viewer viewer(argc, argv, args);
  if (!tutorial::Viewer::accepts(args, 1, argv[0], "[OBJECTS_DIR]"))
    return 1;
  const std::string objects = args.empty() ? VISPMORPH_DATA_DIR "/objects" : args[0];
  try {
    //! [Build]
    // One template per image (named after the file: the six tools and a deformed version of each); the
    // acceptance thresholds are calibrated from the templates themselves (noise, new views and occlusions of
    // each one). Save it with db.save("db.json"), read it back with vpMorphDatabase::load("db.json").
    vpMorphDatabase db = vpMorphDatabase::fromImages(objects);
    //! [Build]
    std::cout << "database: " << db.size() << " templates from " << objects << std::endl;

    //! [Query]
    // The key, its tip hidden by a white card, seen rotated by 120 deg and shifted, with sensor noise.
    vpImage<unsigned char> key;
    vpImageIo::read(key, objects + "/key.png");
    for (unsigned int v = 215; v < 285; ++v)
      for (unsigned int u = 425; u < 480; ++u)
        key[v][u] = 255;
    vpImage<unsigned char> query = newView(key, 120.0 * M_PI / 180.0, 30, -20);
    vpGaussRand noise(10.0, 0.0, 42);
    for (unsigned int k = 0; k < query.getSize(); ++k)
      query.bitmap[k] = static_cast<unsigned char>(std::min(255.0, std::max(0.0, query.bitmap[k] + noise())));
    //! [Query]

    //! [Recognize]
    // The template that costs the least morph work; accepted if that work is within its calibrated threshold.
    // db[r.index].cdMo() is where the camera must go, r.correspondence feeds vpMorph for the virtual images.
    const vpMorphContour qc = vpMorphContourExtractor().extract(query);
    const vpMorphRecognition r = db.recognize(qc);
    std::cout << "query: " << (r.accepted ? "recognised as " : "rejected, closest is ") << db[r.index].name()
              << " (distance " << r.distance << ", threshold " << r.threshold << ", runner-up "
              << db[r.secondIndex].name() << " at " << r.secondDistance << ")" << std::endl;
    //! [Recognize]

    //! [Occluded]
    // The wedge with a grey card biting a square notch into its lower side. A notch costs more work than the
    // thresholds allow (they were calibrated on straight-edged occluders); the view is still accepted because, laid
    // on its best template, it shows at least db.minimumSupport() (0.75) of that template's outline.
    vpImage<unsigned char> wedge;
    vpImageIo::read(wedge, objects + "/wedge.png");
    unsigned int bottom = wedge.getHeight() - 1;
    while (bottom > 0 && wedge[bottom][380] >= 128)
      --bottom;
    for (unsigned int v = bottom - 26; v <= bottom + 26; ++v)
      for (unsigned int u = 380 - 26; u <= 380 + 26; ++u)
        wedge[v][u] = 170;
    const vpMorphContour wc = vpMorphContourExtractor().extract(wedge);
    const vpMorphRecognition w = db.recognize(wc);
    std::cout << "wedge: " << (w.accepted ? "recognised as " : "rejected, closest is ") << db[w.index].name()
              << " (distance " << w.distance << ", threshold " << w.threshold;
    if (!std::isnan(w.support))
      std::cout << "; it shows " << std::lround(100.0 * w.support) << " % of the template's outline";
    std::cout << ")" << std::endl;
    //! [Occluded]

    //! [Unknown]
    // A crescent moon is none of the tools: its best template costs too much work and it is rejected.
    vpImage<unsigned char> moon(480, 640, 255);
    for (unsigned int v = 0; v < moon.getHeight(); ++v)
      for (unsigned int u = 0; u < moon.getWidth(); ++u)
        if (std::hypot(u - 320.0, v - 240.0) < 120.0 && std::hypot(u - 380.0, v - 220.0) > 110.0)
          moon[v][u] = 0;
    const vpMorphContour mc = vpMorphContourExtractor().extract(moon);
    const vpMorphRecognition m = db.recognize(mc);
    std::cout << "moon:  " << (m.accepted ? "recognised as " : "rejected, closest is ") << db[m.index].name()
              << " (distance " << m.distance << ", threshold " << m.threshold << ")" << std::endl;
    //! [Unknown]

    //! [Part]
    // A robot naming the part in front of it: the exact rigid part first (the outline laid on its template through a
    // homography, look-alikes told apart or the view rejected as ambiguous), the database's distance only where no
    // template fits the view rigidly (a bent object).
    const vpMorphPartRecognizer parts(db);
    vpMorphPartRecognizer::Stage stage;
    const vpMorphRecognition p = parts.recognize(wc, &stage);
    std::cout << "wedge, as a part: " << (p.accepted ? "recognised as " : "rejected, closest is ") << db[p.index].name()
              << (stage == vpMorphPartRecognizer::RIGID_STAGE ? " by the rigid check" : " by the distance")
              << std::endl;
    //! [Part]

    //! [Display]
    show(viewer, query, 0, 0, "key", qc, db, r);
    show(viewer, wedge, 660, 0, "wedge", wc, db, w);
    show(viewer, moon, 1320, 0, "moon", mc, db, m);
    viewer.save();
    viewer.waitClick(query);
    //! [Display]

    const bool ok = r.accepted && db[r.index].name().rfind("key", 0) == 0 && w.accepted &&
                    db[w.index].name().rfind("wedge", 0) == 0 && !m.accepted && p.accepted && p.index == w.index;
    return ok ? 0 : 1;
  } catch (const vpException &e) {
    std::cerr << "tutorial-morph-recognition: " << e.getStringMessage() << std::endl;
    return 1;
  }
}
