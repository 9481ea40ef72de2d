// Tests of the simulated scenes (vpMorphPlanarScene, vpMorphTagTexture, vpMorphTagPoseEstimator): tag textures,
// deterministic rendering, contour ground truth, tag ground truth, fault injection and bad input.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <thread>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpMeterPixelConversion.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphJointFile.h>
#include <visp3/morph_sim/vpMorphPlanarScene.h>
#include <visp3/morph_sim/vpMorphTagTexture.h>
#include <visp3/morph_sim/vpMorphThreadCpuClock.h>

namespace
{
std::string object(const std::string &name) { return std::string(VISPMORPH_DATA_DIR) + "/objects/" + name + ".png"; }

// Camera at depth z looking at the plane, turned by rz about the optical axis, tilted by rx, translated (tx, ty).
vpHomogeneousMatrix view(double tx, double ty, double z, double rxDeg, double ryDeg, double rzDeg)
{
  return vpHomogeneousMatrix(tx, ty, z, 0, 0, 0) *
         vpHomogeneousMatrix(0, 0, 0, vpMath::rad(rxDeg), vpMath::rad(ryDeg), vpMath::rad(rzDeg));
}

double segmentDistance(double px, double py, double ax, double ay, double bx, double by)
{
  const double dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
  const double t = l2 > 0 ? std::min(1.0, std::max(0.0, ((px - ax) * dx + (py - ay) * dy) / l2)) : 0.0;
  return std::hypot(px - ax - t * dx, py - ay - t * dy);
}

double polygonDistance(double px, double py, const vpMorphContour &c)
{
  double d = std::numeric_limits<double>::max();
  for (size_t k = 0; k < c.size(); ++k) {
    const size_t l = (k + 1) % c.size();
    d = std::min(d, segmentDistance(px, py, c.x(k), c.y(k), c.x(l), c.y(l)));
  }
  return d;
}

// Symmetric contour error: mean and max vertex-to-polygon distance both ways (pixels).
void contourError(const vpMorphContour &a, const vpMorphContour &b, double &mean, double &maxd)
{
  double sum = 0;
  size_t n = 0;
  maxd = 0;
  for (int pass = 0; pass < 2; ++pass) {
    const vpMorphContour &p = pass ? b : a, &q = pass ? a : b;
    const vpMorphContour dense = p.resampled(200);
    for (size_t k = 0; k < dense.size(); ++k) {
      const double d = polygonDistance(dense.x(k), dense.y(k), q);
      sum += d;
      maxd = std::max(maxd, d);
      ++n;
    }
  }
  mean = sum / n;
}

template <typename T> bool same(const vpImage<T> &a, const vpImage<T> &b)
{
  return a.getWidth() == b.getWidth() && a.getHeight() == b.getHeight() &&
         std::equal(reinterpret_cast<const unsigned char *>(a.bitmap),
                    reinterpret_cast<const unsigned char *>(a.bitmap + a.getSize()),
                    reinterpret_cast<const unsigned char *>(b.bitmap));
}

// The extracted region nearest the ground-truth centroid (the tag's black border is a dark region too).
vpMorphContour extractObject(const vpImage<unsigned char> &I, const vpMorphContour &truth)
{
  double tx, ty;
  truth.centroid(tx, ty);
  vpMorphContour best;
  double bestD = std::numeric_limits<double>::max();
  for (const vpMorphContour &c : vpMorphContourExtractor().extractAll(I)) {
    double cx, cy;
    c.centroid(cx, cy);
    if (std::hypot(cx - tx, cy - ty) < bestD) {
      bestD = std::hypot(cx - tx, cy - ty);
      best = c;
    }
  }
  return best;
}
} // namespace

TEST_CASE("tag texture from libapriltag: black border, quiet zone, exact tag size", "[morph_sim][tag]")
{
  const vpImage<unsigned char> T = vpMorphTagTexture::create(3, 10);
  REQUIRE(T.getWidth() == 100);
  REQUIRE(T.getHeight() == 100);
  for (unsigned int k = 0; k < 100; ++k) {
    CHECK(T[0][k] == 255); // quiet zone
    CHECK(T[k][99] == 255);
    if (k >= 10 && k < 90) {
      CHECK(T[10][k] == 0); // black border
      CHECK(T[k][89] == 0);
    }
  }
  CHECK(vpMorphTagTexture::tagSizeForTextureSide(0.099, 10) == Approx(0.08));
  CHECK(vpMorphTagTexture::textureSideForTagSize(vpMorphTagTexture::tagSizeForTextureSide(0.07, 4), 4) == Approx(0.07));
  CHECK_THROWS_AS(vpMorphTagTexture::create(587), vpMorphException);
  CHECK_THROWS_AS(vpMorphTagTexture::create(-1), vpMorphException);
  CHECK_THROWS_AS(vpMorphTagTexture::tagSizeForTextureSide(0.0), vpMorphException);
  CHECK_THROWS_AS(vpMorphTagTexture::textureSideForTagSize(std::nan("")), vpMorphException);
}

TEST_CASE("rendering is deterministic, grey and colour", "[morph_sim][scene]")
{
  vpMorphPlanarScene scene(object("pliers"));
  const vpHomogeneousMatrix cMo = view(0.01, -0.02, 0.5, 5, -3, 40);
  vpImage<unsigned char> I1, I2;
  scene.render(cMo, I1);
  scene.render(cMo, I2);
  REQUIRE(I1.getWidth() == 640);
  REQUIRE(I1.getHeight() == 480);
  CHECK(same(I1, I2));
  vpImage<vpRGBa> C1, C2;
  scene.render(cMo, C1);
  scene.render(cMo, C2);
  CHECK(same(C1, C2));
  // A copy of the scene renders the same; with noise, the same frame is the same and another frame differs.
  vpMorphPlanarScene::Faults f;
  f.noiseSigma = 4;
  f.seed = 7;
  scene.setFaults(f);
  const vpMorphPlanarScene copy = scene;
  scene.render(cMo, I1, 3);
  copy.render(cMo, I2, 3);
  CHECK(same(I1, I2));
  copy.render(cMo, I2, 4);
  CHECK_FALSE(same(I1, I2));
}

TEST_CASE("rendering and tag detection give the same results from two threads", "[morph_sim][scene]")
{
  // The benchmark runs scenarios on both cores: nothing in a scene or an estimator is shared between calls.
  const vpMorphPlanarScene scene(object("wrench"));
  const vpHomogeneousMatrix cMo = view(0.01, 0.02, 0.5, 5, 5, 60);
  vpImage<unsigned char> ref;
  scene.render(cMo, ref);
  vpHomogeneousMatrix refPose;
  REQUIRE(scene.tagPoseEstimator().estimate(ref, refPose));
  vpImage<unsigned char> I[2];
  vpHomogeneousMatrix pose[2];
  bool found[2] = {false, false};
  std::thread workers[2];
  for (int k = 0; k < 2; ++k)
    workers[k] = std::thread([&, k] {
      for (int it = 0; it < 3; ++it) {
        scene.render(cMo, I[k]);
        found[k] = scene.tagPoseEstimator().estimate(I[k], pose[k]);
      }
    });
  for (auto &w : workers)
    w.join();
  for (int k = 0; k < 2; ++k) {
    CHECK(same(I[k], ref));
    CHECK(found[k]);
    for (unsigned int i = 0; i < 4; ++i)
      for (unsigned int j = 0; j < 4; ++j)
        CHECK(pose[k][i][j] == refPose[i][j]);
  }
  // The colour render draws the object in blue.
  vpImage<vpRGBa> C;
  scene.render(view(0, 0, 0.5, 0, 0, 0), C);
  const vpMorphContour truth = scene.projectedContour(view(0, 0, 0.5, 0, 0, 0));
  double cx, cy;
  truth.centroid(cx, cy);
  size_t blue = 0;
  for (size_t k = 0; k < truth.size(); ++k) {
    // Points a quarter of the way from the centroid to each vertex: mostly inside the object.
    const vpRGBa p = C[static_cast<unsigned int>(cy + 0.25 * (truth.y(k) - cy))]
                      [static_cast<unsigned int>(cx + 0.25 * (truth.x(k) - cx))];
    blue += (p.B > p.R + 50) ? 1 : 0;
  }
  CHECK(blue > truth.size() / 2);
}

TEST_CASE("extracted contour of the rendered object matches the projected ground truth", "[morph_sim][scene]")
{
  for (const std::string name : {"pliers", "key", "wedge", "wrench", "screwdriver", "hammer"}) {
    vpMorphPlanarScene scene(object(name));
    const vpHomogeneousMatrix poses[] = {view(0, 0, 0.5, 0, 0, 0), view(0.03, -0.02, 0.5, 0, 0, 120),
                                         view(-0.02, 0.01, 0.45, 15, -10, -70), view(0.0, 0.0, 0.65, 0, 20, 180)};
    for (const vpHomogeneousMatrix &cMo : poses) {
      vpImage<unsigned char> I;
      scene.render(cMo, I);
      const vpMorphContour truth = scene.projectedContour(cMo);
      const vpMorphContour found = extractObject(I, truth);
      double mean, maxd;
      contourError(found, truth, mean, maxd);
      INFO(name << " at " << vpPoseVector(cMo).t() << ": contour error mean " << mean << " px, max " << maxd << " px");
      CHECK(mean < 0.8);
      CHECK(maxd < 4.0);
      CHECK(found.area() == Approx(truth.area()).epsilon(0.03));
    }
  }
}

TEST_CASE("a pixel integrates the texture: a fine texture is drawn as one at the view's size", "[morph_sim][scene]")
{
  // One 15 cm disc as two textures: 1200 texels across (5 texels a pixel of the view from 0.5 m) and 240 (1.25),
  // each texel grey by the share of it the disc covers (16 x 16 samples), 8 texels of ground around.
  const auto disc = [](unsigned int side, const std::string &path) {
    const double c = 0.5 * (side - 1.0), r = 0.5 * (side - 16.0);
    vpImage<unsigned char> I(side, side);
    for (unsigned int i = 0; i < side; ++i)
      for (unsigned int j = 0; j < side; ++j) {
        int in = 0;
        for (int a = 0; a < 16; ++a)
          for (int b = 0; b < 16; ++b)
            in += std::hypot(i - 0.5 + (a + 0.5) / 16 - c, j - 0.5 + (b + 0.5) / 16 - c) < r;
        I[i][j] = static_cast<unsigned char>(std::lround(255.0 * (1.0 - in / 256.0)));
      }
    vpImageIo::write(I, path);
    return vpMorphPlanarScene(path);
  };
  const vpMorphPlanarScene fine = disc(1216, "disc-fine.png"), coarse = disc(256, "disc-coarse.png");
  // RMS distance (px) of the extracted outline to the disc's projected circle (views normal to the plane).
  const auto error = [](const vpMorphPlanarScene &scene, unsigned int side, const vpHomogeneousMatrix &cMo) {
    vpImage<unsigned char> I;
    scene.render(cMo, I);
    const double c = 0.5 * (side - 1.0), r = 0.5 * (side - 16.0);
    const vpImagePoint o = scene.projectedTexel(c, c, cMo), e = scene.projectedTexel(c + r, c, cMo);
    const double R = vpImagePoint::distance(o, e);
    const vpMorphContour outline = extractObject(I, scene.projectedContour(cMo)).outline();
    double sum = 0;
    for (std::size_t k = 0; k < outline.size(); ++k) {
      const double d = std::hypot(outline.x(k) - o.get_u(), outline.y(k) - o.get_v()) - R;
      sum += d * d;
    }
    return std::sqrt(sum / outline.size());
  };
  for (const vpHomogeneousMatrix &cMo : {view(0, 0, 0.5, 0, 0, 0), view(0.01, -0.02, 0.45, 0, 0, 30)}) {
    CHECK(fine.supersampling(cMo) == 3);
    CHECK(coarse.supersampling(cMo) == 1);
    // Within a twentieth of a pixel, as the texture at the view's size; sampled at pixel centres, 0.16-0.2 px.
    CHECK(error(fine, 1216, cMo) < 0.05);
    CHECK(error(coarse, 256, cMo) < 0.07);
  }
  // In colour too: the same pixels, each the same share of object and plane as in grey.
  const vpHomogeneousMatrix cMo = view(0, 0, 0.5, 0, 0, 0);
  vpImage<unsigned char> I;
  vpImage<vpRGBa> C;
  fine.render(cMo, I);
  fine.render(cMo, C);
  REQUIRE((C.getWidth() == I.getWidth() && C.getHeight() == I.getHeight()));
  double worst = 0;
  for (unsigned int k = 0; k < I.getSize(); ++k) // the object is (25, 45, 120) in colour, 40 in grey, the plane B 195
    worst = std::max(worst, std::fabs((195.0 - C.bitmap[k].B) / 75.0 - (210.0 - I.bitmap[k]) / 170.0));
  CHECK(worst < 0.02);
}

TEST_CASE("AprilTag pose agrees with the simulator's pose", "[morph_sim][tag]")
{
  vpMorphPlanarScene scene(object("key"), 0.15, 5, 0.08);
  const vpMorphTagPoseEstimator estimator = scene.tagPoseEstimator();
  const vpHomogeneousMatrix poses[] = {view(0, 0, 0.5, 0, 0, 0),           view(0.04, 0.03, 0.5, 0, 0, 90),
                                       view(-0.05, 0.02, 0.5, 0, 0, 180),  view(0.02, -0.03, 0.5, 10, 5, -45),
                                       view(0.0, 0.01, 0.4, -15, 10, 150), view(0.0, 0.0, 0.6, 20, 0, 30)};
  double worstT = 0, worstR = 0;
  for (const vpHomogeneousMatrix &cMo : poses) {
    vpImage<unsigned char> I;
    scene.render(cMo, I);
    vpHomogeneousMatrix cMo_tag;
    std::vector<vpImagePoint> corners;
    REQUIRE(estimator.estimate(I, cMo_tag, &corners));
    double t, r;
    vpMorphTagPoseEstimator::poseDifference(cMo_tag, cMo, t, r);
    worstT = std::max(worstT, t);
    worstR = std::max(worstR, r);
    INFO("pose " << vpPoseVector(cMo).t() << ": tag vs simulator " << t * 1000 << " mm, " << vpMath::deg(r) << " deg");
    CHECK(t < 0.002);
    CHECK(vpMath::deg(r) < 0.5);
    // The detected corners are the projected ones, in the same order.
    const std::vector<vpImagePoint> truth = scene.projectedTagCorners(cMo);
    REQUIRE(corners.size() == 4);
    for (size_t k = 0; k < 4; ++k) {
      INFO("corner " << k << " detected " << corners[k] << " projected " << truth[k]);
      CHECK(vpImagePoint::distance(corners[k], truth[k]) < 0.7);
    }
  }
  INFO("worst disagreement " << worstT * 1000 << " mm, " << vpMath::deg(worstR) << " deg");
  CHECK(worstT < 0.002);
}

TEST_CASE("the silhouette is recognised among the first view's regions, then followed past a larger one",
          "[morph_sim][tag]")
{
  vpMorphPlanarScene scene(object("pliers"));
  scene.setTagPlacement(0.0, -0.1);
  vpMorphPlanarScene::Faults f;
  f.noiseSigma = 2;
  f.largeDistractorArea = 1.4 * scene.objectArea();
  f.largeDistractorAspect = 1.5;
  f.largeDistractorX = 0.14;
  f.largeDistractorY = 0.02;
  f.largeDistractorAngle = M_PI / 2;
  scene.setFaults(f);
  auto look = [&scene](const vpHomogeneousMatrix &cMo, vpImage<unsigned char> &I, std::vector<vpImagePoint> &corners) {
    scene.render(cMo, I);
    vpHomogeneousMatrix cMo_tag;
    REQUIRE(scene.tagPoseEstimator().estimate(I, cMo_tag, &corners));
  };
  const vpHomogeneousMatrix first = view(0.01, -0.01, 0.5, 3, 0, 10), second = view(0.013, -0.008, 0.498, 3, 0, 10.5);
  vpImage<unsigned char> I;
  std::vector<vpImagePoint> corners;
  look(first, I, corners);
  double m, mx;
  contourError(vpMorphTagPoseEstimator::silhouette(I, corners), scene.projectedContour(first), m, mx);
  REQUIRE(m > 10); // the largest region is the distractor (joined with the object or not)
  // The first view: one of the candidates is the object, which a template database tells apart.
  double ms = -1;
  const std::vector<vpMorphContour> cands = vpMorphTagPoseEstimator::silhouetteCandidates(I, corners, &ms);
  CHECK(ms >= 0);
  vpMorphContour previous;
  for (const vpMorphContour &c : cands) {
    contourError(c, scene.projectedContour(first), m, mx);
    if (m < 0.8)
      previous = c;
  }
  REQUIRE_FALSE(previous.empty());
  // The next view: the silhouette that continues it is the object's, region measured.
  look(second, I, corners);
  const vpMorphContour next = vpMorphTagPoseEstimator::silhouette(I, corners, previous, &ms);
  contourError(next, scene.projectedContour(second), m, mx);
  CHECK(m < 0.8);
  CHECK(next.hasRegion());
  // Where nothing is, an empty silhouette (a control loop holds); no object at all: no candidate.
  CHECK(vpMorphTagPoseEstimator::silhouette(I, corners, previous.transformed(0, -1000, 0)).empty());
  CHECK(vpMorphTagPoseEstimator::silhouetteCandidates(vpImage<unsigned char>(48, 64, 128), {}).empty());
}

TEST_CASE("masking the detected tag leaves the object as the largest region", "[morph_sim][tag]")
{
  vpMorphPlanarScene scene(object("pliers"));
  vpMorphPlanarScene::Faults f;
  f.noiseSigma = 2;
  scene.setFaults(f);
  const vpHomogeneousMatrix cMo = view(0.02, -0.01, 0.5, 5, 0, 110);
  vpImage<unsigned char> I;
  scene.render(cMo, I);
  const vpMorphContour truth = scene.projectedContour(cMo);
  double m, mx;
  contourError(vpMorphContourExtractor().extract(I), truth, m, mx);
  CHECK(m > 10); // the tag is the largest dark region
  vpHomogeneousMatrix cMo_tag;
  std::vector<vpImagePoint> corners;
  REQUIRE(scene.tagPoseEstimator().estimate(I, cMo_tag, &corners));
  // The pipeline every controller uses: mask, extract; the polygon comes with its measured region.
  double ms = -1;
  const vpMorphContour s = vpMorphTagPoseEstimator::silhouette(I, corners, &ms);
  contourError(s, truth, m, mx);
  CHECK(m < 0.8);
  CHECK(ms >= 0);
  CHECK(s.hasRegion());
  // Without corners nothing is masked (the tag wins); an image without object gives an empty silhouette.
  contourError(vpMorphTagPoseEstimator::silhouette(I, {}), truth, m, mx);
  CHECK(m > 10);
  CHECK(vpMorphTagPoseEstimator::silhouette(vpImage<unsigned char>(48, 64, 128), {}).empty());
  vpMorphTagPoseEstimator::maskTag(I, corners);
  contourError(vpMorphContourExtractor().extract(I), truth, m, mx);
  INFO("contour error after masking the tag: mean " << m << " px, max " << mx << " px");
  CHECK(m < 0.8);
  CHECK(mx < 4.0);
  CHECK_THROWS_AS(vpMorphTagPoseEstimator::maskTag(I, std::vector<vpImagePoint>(3)), vpMorphException);
}

TEST_CASE("the tag's mask carries the plane's shading under a light that falls off across the view",
          "[morph_sim][tag][light]")
{
  // The plane (210) under a gain of 1 + 0.4 d, d the position along 20 deg over the half diagonal: across the tag the
  // plane's level changes by about 25 grey levels, which a single fill level leaves as steps at the square's sides.
  vpMorphPlanarScene scene(std::string(VISPMORPH_DATA_DIR) + "/objects/wrench.png");
  vpMorphPlanarScene::Faults f;
  f.gradient = 0.4;
  f.gradientAngle = vpMath::rad(20);
  scene.setFaults(f);
  const vpHomogeneousMatrix cMo(0.01, -0.005, 0.5, 0, 0, vpMath::rad(10));
  vpImage<unsigned char> I;
  scene.render(cMo, I, 0);
  vpImage<unsigned char> J = I;
  vpMorphTagPoseEstimator::maskTag(J, scene.projectedTagCorners(cMo));
  const double cu = 0.5 * (I.getWidth() - 1), cv = 0.5 * (I.getHeight() - 1), half = std::hypot(cu, cv);
  double worst = 0.0;
  long painted = 0;
  for (unsigned int v = 0; v < I.getHeight(); ++v)
    for (unsigned int u = 0; u < I.getWidth(); ++u)
      if (J[v][u] != I[v][u]) {
        const double d = ((u - cu) * std::cos(f.gradientAngle) + (v - cv) * std::sin(f.gradientAngle)) / half;
        const double gain = 1.0 + f.gradient * d;
        worst = std::max(worst, std::fabs(J[v][u] - 210.0 * gain));
        ++painted;
      }
  INFO(painted << " pixels painted, the farthest " << worst << " grey levels from the plane's");
  REQUIRE(painted > 1000);
  CHECK(worst < 3.0);
}

TEST_CASE("image noise, blur and illumination change are applied as specified", "[morph_sim][faults]")
{
  vpMorphPlanarScene scene(object("wedge"));
  const vpHomogeneousMatrix cMo = view(0, 0, 0.5, 0, 0, 0);
  vpImage<unsigned char> clean, I;
  scene.render(cMo, clean);
  const unsigned char bg = clean[5][5];
  CHECK(bg == 210);

  vpMorphPlanarScene::Faults f;
  f.noiseSigma = 5.0;
  scene.setFaults(f);
  scene.render(cMo, I);
  double s = 0, s2 = 0;
  for (unsigned int k = 0; k < I.getSize(); ++k) {
    const double d = static_cast<double>(I.bitmap[k]) - clean.bitmap[k];
    s += d;
    s2 += d * d;
  }
  const double n = I.getSize(), mean = s / n, sd = std::sqrt(s2 / n - mean * mean);
  INFO("noise mean " << mean << " std " << sd);
  CHECK(std::fabs(mean) < 0.1);
  CHECK(sd == Approx(5.0).epsilon(0.05));

  f = vpMorphPlanarScene::Faults();
  f.gain = 0.7;
  f.offset = 20;
  scene.setFaults(f);
  scene.render(cMo, I);
  CHECK(I[5][5] == static_cast<unsigned char>(std::lround(0.7 * 210 + 20)));

  f = vpMorphPlanarScene::Faults();
  f.blurSigma = 2.0;
  scene.setFaults(f);
  scene.render(cMo, I);
  CHECK_FALSE(same(I, clean));
  CHECK(I[5][5] == bg); // flat areas keep their level
  // The blurred object is still extracted close to the truth.
  const vpMorphContour truth = scene.projectedContour(cMo);
  double cm, cx;
  contourError(extractObject(I, truth), truth, cm, cx);
  INFO("blurred contour error mean " << cm << " max " << cx);
  CHECK(cm < 1.0);
}

TEST_CASE("the occluder hides the requested share of the contour", "[morph_sim][faults]")
{
  vpMorphPlanarScene scene(object("pliers"));
  const vpHomogeneousMatrix cMo = view(0.01, 0.0, 0.5, 0, 0, 30);
  vpImage<unsigned char> clean, I;
  scene.render(cMo, clean);
  for (double share : {0.05, 0.1, 0.2}) {
    for (double where : {0.0, 0.3, 0.7}) {
      vpMorphPlanarScene::Faults f;
      f.occludedShare = share;
      f.occluderPosition = where;
      scene.setFaults(f);
      INFO("requested " << share << " at " << where << ", measured " << scene.occludedShare());
      CHECK(scene.occludedShare() == Approx(share).margin(0.01));
      REQUIRE(scene.occluderCorners3D().size() == 4);
      scene.render(cMo, I);
      // Measured in the image: contour points nudged 0.8 mm inwards are dark (object) unless occluded (170).
      std::vector<vpPoint> P = scene.objectContour3D();
      std::vector<double> x, y;
      for (const vpPoint &p : P) {
        x.push_back(p.get_oX());
        y.push_back(p.get_oY());
      }
      const vpMorphContour c(x, y, vpMorphContour::NORMALIZED);
      const double sign =
          c.isCounterClockwise() ? 1.0 : -1.0; // inward normal is to the left when CCW (x right, y down)
      const vpMorphContour dense = c.resampled(600);
      size_t hidden = 0, counted = 0;
      for (size_t k = 0; k < dense.size(); ++k) {
        const size_t l = (k + 1) % dense.size();
        const double dx = dense.x(l) - dense.x(k), dy = dense.y(l) - dense.y(k), len = std::hypot(dx, dy);
        vpPoint q;
        q.setWorldCoordinates(dense.x(k) - sign * dy / len * 0.0008, dense.y(k) + sign * dx / len * 0.0008, 0);
        q.track(cMo);
        double u, v;
        vpMeterPixelConversion::convertPoint(scene.camera(), q.get_x(), q.get_y(), u, v);
        const unsigned char was = clean[static_cast<unsigned int>(v + 0.5)][static_cast<unsigned int>(u + 0.5)];
        if (was > 100)
          continue; // the nudge left the object (thin part): not a usable probe
        ++counted;
        hidden += I[static_cast<unsigned int>(v + 0.5)][static_cast<unsigned int>(u + 0.5)] > 100 ? 1 : 0;
      }
      const double measured = static_cast<double>(hidden) / counted;
      INFO("image-measured share " << measured << " over " << counted << " probes");
      CHECK(counted > 400);
      CHECK(measured == Approx(share).margin(0.04));
    }
  }
}

TEST_CASE("distractors are placed clear of the object and the tag", "[morph_sim][faults]")
{
  vpMorphPlanarScene scene(object("hammer"));
  const vpHomogeneousMatrix cMo = view(0, 0, 0.5, 0, 0, 0);
  vpImage<unsigned char> clean, I;
  scene.render(cMo, clean);
  const size_t before = vpMorphContourExtractor().extractAll(clean).size();
  vpMorphPlanarScene::Faults f;
  f.distractors = 4;
  f.seed = 11;
  scene.setFaults(f);
  REQUIRE(scene.distractorCorners3D().size() == 4);
  scene.render(cMo, I);
  const std::vector<vpMorphContour> all = vpMorphContourExtractor().extractAll(I);
  CHECK(all.size() >= before + 3); // one may leave the field of view
  const vpMorphContour truth = scene.projectedContour(cMo);
  double m, mx;
  contourError(extractObject(I, truth), truth, m, mx);
  CHECK(m < 0.8);
  // Another seed, another layout; the same seed, the same layout.
  vpMorphPlanarScene other = scene;
  f.seed = 12;
  other.setFaults(f);
  CHECK(other.distractorCorners3D()[0][0].get_oX() != scene.distractorCorners3D()[0][0].get_oX());
}

TEST_CASE("object and tag in view", "[morph_sim][scene]")
{
  vpMorphPlanarScene scene(object("wrench"));
  CHECK(scene.objectInView(view(0, 0, 0.5, 0, 0, 0)));
  CHECK(scene.tagInView(view(0, 0, 0.5, 0, 0, 0)));
  CHECK_FALSE(scene.objectInView(view(0.25, 0, 0.5, 0, 0, 0)));   // shifted out of the image
  CHECK_FALSE(scene.objectInView(view(0, 0, 0.5, 0, 0, 0), 300)); // margin larger than half the image
  CHECK_FALSE(scene.objectInView(view(0, 0, -0.5, 0, 0, 0)));     // behind the camera
  CHECK_THROWS_AS(scene.tagInView(view(0, 0, 0.5, 0, 0, 0), std::nan("")), vpMorphException);
}

TEST_CASE("a deformed object in its template's frame keeps its undeformed part in place", "[morph_sim][scene]")
{
  // The key's blade is bent, its bow is not: in the template's frame the bow outlines coincide; in its own frame
  // (centroid and size of the bent key) the bow moves with the bend.
  const vpHomogeneousMatrix cMo = view(0, 0, 0.5, 0, 0, 0);
  const vpMorphPlanarScene keyScene(object("key"));
  vpMorphPlanarScene own(object("key-deformed")), framed(object("key-deformed"));
  framed.setReferenceImage(object("key"));
  CHECK(framed.metresPerTexel() == Approx(keyScene.metresPerTexel()).epsilon(1e-12));
  const vpMorphContour ref = keyScene.projectedContour(cMo);
  double xmin = ref.x(0);
  for (size_t k = 0; k < ref.size(); ++k)
    xmin = std::min(xmin, ref.x(k));
  auto bowError = [&](const vpMorphPlanarScene &s) {
    const vpMorphContour c = s.projectedContour(cMo).resampled(400);
    double worst = 0;
    for (size_t k = 0; k < c.size(); ++k)
      if (c.x(k) < xmin + 30) // the bow: the leftmost 30 px (the bend starts past it)
        worst = std::max(worst, polygonDistance(c.x(k), c.y(k), ref));
    return worst;
  };
  // Within a pixel (two polygonisations of one digitised outline; measured 0.51 px), where its own frame is 7 px off.
  CAPTURE(bowError(framed), bowError(own));
  CHECK(bowError(framed) < 1.0);
  CHECK(bowError(own) > 3.0);
  // A reference of its own image changes nothing.
  vpMorphPlanarScene same(object("key"));
  same.setReferenceImage(object("key"));
  double mean = 0, maxd = 0;
  contourError(same.projectedContour(cMo), ref, mean, maxd);
  CHECK(maxd < 1e-9);
  CHECK_THROWS_AS(framed.setReferenceImage(object("no-such-object")), vpMorphException);
}

TEST_CASE("a deformed object placed by best overlap lies on its template as well as a rigid move can",
          "[morph_sim][scene][overlap]")
{
  // Seen from one pose, the bent object's silhouette covers more of the template's than in the shared frame (where
  // only the part drawn undeformed lies on it), and no small rigid move of it covers more.
  const vpHomogeneousMatrix cMo = view(0, 0, 0.5, 0, 0, 0);
  for (const std::string name : {"key", "hammer", "wrench"}) {
    const vpMorphPlanarScene tpl(object(name));
    vpMorphPlanarScene shared(object(name + "-deformed")), best(object(name + "-deformed"));
    shared.setReferenceImage(object(name));
    best.setReferenceImage(object(name), vpMorphPlanarScene::BEST_OVERLAP);
    CHECK(shared.referenceAlignment().theta() == 0.0);
    CHECK(std::fabs(vpMath::deg(best.referenceAlignment().theta())) > 5.0); // bends of 12-15 deg
    const vpMorphContour ref = tpl.projectedContour(cMo), moved = best.projectedContour(cMo);
    const double f = moved.overlapArea(ref);
    INFO(name << ": overlap " << f / ref.area() << " of the template's area, shared frame "
              << shared.projectedContour(cMo).overlapArea(ref) / ref.area());
    CHECK(f > shared.projectedContour(cMo).overlapArea(ref) + 0.02 * ref.area());
    double cx, cy;
    moved.centroid(cx, cy);
    for (const vpMorphRigidTransform &d :
         {vpMorphRigidTransform(vpMath::rad(0.3), 0, 0, 1, cx, cy),
          vpMorphRigidTransform(vpMath::rad(-0.3), 0, 0, 1, cx, cy), vpMorphRigidTransform(0, 0.5, 0),
          vpMorphRigidTransform(0, -0.5, 0), vpMorphRigidTransform(0, 0, 0.5), vpMorphRigidTransform(0, 0, -0.5)})
      CHECK(d.apply(moved).overlapArea(ref) < f);
  }
}

TEST_CASE("a texture placed by a given motion, its equally good placements, and a texel projected",
          "[morph_sim][scene][overlap]")
{
  const vpHomogeneousMatrix cMo = view(0.01, -0.02, 0.5, 0, 0, 0.4);
  const vpMorphPlanarScene tpl(object("pliers"));
  vpMorphPlanarScene scene(object("pliers"));
  scene.setReferenceImage(object("pliers"));
  CHECK(scene.alternativePlacements().empty());
  // The texture turned by 10 deg about texel (320, 240), and an alternative turned by -20 deg about it.
  const vpMorphRigidTransform A(vpMath::rad(10.0), 0, 0, 1, 320, 240), B(vpMath::rad(-20.0), 0, 0, 1, 320, 240);
  scene.setReferenceAlignment(A, {B});
  CHECK(scene.referenceAlignment().theta() == A.theta());
  // That texel stays where the template shows it; another one turns by 10 deg about it in the image (the camera is
  // parallel to the plane).
  const vpImagePoint pin = tpl.projectedTexel(320, 240, cMo);
  CHECK(vpImagePoint::distance(scene.projectedTexel(320, 240, cMo), pin) < 1e-9);
  const vpImagePoint p0 = tpl.projectedTexel(420, 240, cMo), p1 = scene.projectedTexel(420, 240, cMo);
  const double turn = std::atan2(p1.get_v() - pin.get_v(), p1.get_u() - pin.get_u()) -
                      std::atan2(p0.get_v() - pin.get_v(), p0.get_u() - pin.get_u());
  CHECK(std::fabs(std::fabs(vpMath::deg(std::remainder(turn, 2 * M_PI))) - 10.0) < 1e-6);
  // The alternative as a motion of the object frame: seen from cMo * W, the object shows B's placement.
  const std::vector<vpHomogeneousMatrix> W = scene.alternativePlacements();
  REQUIRE(W.size() == 1);
  vpMorphPlanarScene other(object("pliers"));
  other.setReferenceImage(object("pliers"));
  other.setReferenceAlignment(B);
  for (const std::pair<double, double> t :
       {std::make_pair(320.0, 240.0), std::make_pair(420.0, 240.0), std::make_pair(250.0, 200.0)})
    CHECK(vpImagePoint::distance(scene.projectedTexel(t.first, t.second, cMo * W[0]),
                                 other.projectedTexel(t.first, t.second, cMo)) < 1e-6);
  CHECK_THROWS_AS(scene.projectedTexel(NAN, 240, cMo), vpMorphException);
  CHECK_THROWS_AS(scene.projectedTexel(320, 240, view(0, 0, -0.5, 0, 0, 0)), vpMorphException); // behind
}

TEST_CASE("a taught silhouette with the tag masked, and an articulation seen from a pose", "[morph_sim][scene][joint]")
{
  const vpHomogeneousMatrix cdMo = view(0.01, 0, 0.5, 0, 0, 20);
  const vpMorphPlanarScene scene(object("pliers"));
  // The tag (a larger dark region than the pliers) is masked: the silhouette is the pliers' outline.
  const vpMorphContour c = scene.silhouette(cdMo);
  const vpMorphContour truth = scene.projectedContour(cdMo);
  CHECK(std::fabs(c.area() / truth.area() - 1.0) < 0.02);
  double cx, cy, tx, ty;
  c.centroid(cx, cy);
  truth.centroid(tx, ty);
  CHECK(std::hypot(cx - tx, cy - ty) < 0.5);
  // The tag out of view: nothing to mask, the same pliers.
  vpMorphPlanarScene far(object("pliers"));
  far.setTagPlacement(0.6, 0.6);
  REQUIRE_FALSE(far.tagInView(cdMo));
  CHECK(std::fabs(far.silhouette(cdMo).area() / c.area() - 1.0) < 1e-3);
  // No object in view.
  CHECK_THROWS_AS(scene.silhouette(view(0.5, 0.5, 0.5, 0, 0, 0)), vpMorphException);

  // The pliers' arms as the camera at cdMo sees them: at the taught opening they make the taught view, the pin is
  // the projected texel, the range that of the joint file (the camera does not mirror the texture).
  const std::string data = VISPMORPH_DATA_DIR;
  const vpMorphJointFile joint = vpMorphJointFile::read(data + "/joints/pliers.json");
  const vpMorphArticulation a = scene.articulation(joint, cdMo);
  CHECK(vpImagePoint::distance(a.pivot(), scene.projectedTexel(320, 240, cdMo)) < 1e-9);
  CHECK(a.minAngle() == joint.minAngle());
  CHECK(a.maxAngle() == joint.maxAngle());
  const vpMorphContour closed = a.pose(0.0);
  double px, py, rx, ry;
  closed.regionCentroid(px, py);
  c.regionCentroid(rx, ry);
  CAPTURE(closed.regionArea() / c.regionArea(), std::hypot(px - rx, py - ry));
  CHECK(std::fabs(closed.regionArea() / c.regionArea() - 1.0) < 0.005);
  CHECK(std::hypot(px - rx, py - ry) < 0.1);
  // At 32 deg: the opened pliers laid by arm 0, seen from cdMo.
  vpMorphPlanarScene opened(object("pliers-deformed"));
  opened.setReferenceImage(object("pliers"));
  opened.setReferenceAlignment(vpMorphRigidTransform(vpMath::rad(16.0), 0, 0, 1, 320, 240));
  const vpMorphContour v = opened.silhouette(cdMo);
  CHECK(std::fabs(vpMath::deg(a.estimate(v)) - 32.0) < 0.3);
  vpMorphMatcher matcher;
  const double atOpening = vpMorphArticulation::fitOverlap(v, a.pose(vpMath::rad(32.0)), matcher);
  const double atTaught = vpMorphArticulation::fitOverlap(v, closed, matcher);
  CAPTURE(atOpening, atTaught);
  CHECK(atOpening > 0.9);
  CHECK(atOpening > atTaught + 0.2);
  // A part image of another size than the object's.
  const std::filesystem::path dir = std::filesystem::temp_directory_path();
  vpImage<unsigned char> small(240, 320, 255);
  for (unsigned int r = 100; r < 140; ++r)
    for (unsigned int k = 100; k < 220; ++k)
      small[r][k] = 0;
  vpImageIo::write(small, (dir / "joint-small-part.png").string());
  std::ofstream(dir / "joint-bad-size.json") << "{\"parts\": [\"" << data
                                             << "/joints/pliers-part0.png\", \"joint-small-part.png\"], "
                                                "\"pivot\": [320, 240], \"range_deg\": [-8, 60]}";
  CHECK_THROWS_AS(scene.articulation(vpMorphJointFile::read((dir / "joint-bad-size.json").string()), cdMo),
                  vpMorphException);
  std::filesystem::remove(dir / "joint-bad-size.json");
  std::filesystem::remove(dir / "joint-small-part.png");
}

TEST_CASE("bad scene input throws vpMorphException", "[morph_sim][errors]")
{
  CHECK_THROWS_AS(vpMorphPlanarScene(object("no-such-object")), vpMorphException);
  CHECK_THROWS_AS(vpMorphPlanarScene(object("pliers"), 0.0), vpMorphException);
  CHECK_THROWS_AS(vpMorphPlanarScene(object("pliers"), -0.1), vpMorphException);
  CHECK_THROWS_AS(vpMorphPlanarScene(object("pliers"), std::nan("")), vpMorphException);
  CHECK_THROWS_AS(vpMorphPlanarScene(object("pliers"), 0.15, 0, 0.0), vpMorphException);
  CHECK_THROWS_AS(vpMorphPlanarScene(object("pliers"), 0.15, 900), vpMorphException);
  vpMorphPlanarScene scene(object("pliers"));
  vpHomogeneousMatrix bad(0, 0, 0.5, 0, 0, 0);
  bad[0][3] = std::nan("");
  vpImage<unsigned char> I;
  CHECK_THROWS_AS(scene.render(bad, I), vpMorphException);
  CHECK_THROWS_AS(scene.projectedContour(bad), vpMorphException);
  CHECK_THROWS_AS(scene.supersampling(bad), vpMorphException);
  CHECK_THROWS_AS(scene.setObjectPlacement(0, std::nan(""), 0), vpMorphException);
  vpMorphPlanarScene::Faults f;
  f.occludedShare = 0.95;
  CHECK_THROWS_AS(scene.setFaults(f), vpMorphException);
  f = vpMorphPlanarScene::Faults();
  f.noiseSigma = -1;
  CHECK_THROWS_AS(scene.setFaults(f), vpMorphException);
  f = vpMorphPlanarScene::Faults();
  f.gain = 0;
  CHECK_THROWS_AS(scene.setFaults(f), vpMorphException);
}

TEST_CASE("the silhouette joins the pieces an occluder cut from the object", "[morph_sim][faults]")
{
  // A card across a thin tool leaves two pieces: every controller must get the whole visible object, not the
  // larger piece alone (a cut-off pliers head was recognised as a wedge).
  vpMorphPlanarScene scene(object("pliers"));
  const vpHomogeneousMatrix cMo = view(0.01, 0.0, 0.5, 0, 0, 30);
  vpImage<unsigned char> I;
  int severed = 0;
  for (double where : {0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9}) {
    vpMorphPlanarScene::Faults f;
    f.occludedShare = 0.15;
    f.occluderPosition = where;
    scene.setFaults(f);
    scene.render(cMo, I);
    std::vector<vpImagePoint> corners;
    vpHomogeneousMatrix cMo_tag;
    REQUIRE(scene.tagPoseEstimator().estimate(I, cMo_tag, &corners));
    const vpMorphContour s = vpMorphTagPoseEstimator::silhouette(I, corners);
    vpImage<unsigned char> J = I;
    vpMorphTagPoseEstimator::maskTag(J, corners);
    const std::vector<vpMorphContour> pieces = vpMorphContourExtractor().extractAll(J);
    REQUIRE(!pieces.empty());
    INFO("occluder at " << where << ": " << pieces.size() << " regions, silhouette area " << s.area()
                        << ", largest piece " << pieces[0].area());
    CHECK(s.area() >= 0.99 * pieces[0].area());
    if (pieces.size() > 1 && pieces[1].area() > 0.1 * pieces[0].area()) {
      ++severed;
      CHECK(s.area() > pieces[0].area() + 0.9 * pieces[1].area());
    }
  }
  CHECK(severed > 0); // the card did cut the tool somewhere
}

TEST_CASE("the benchmark's clock counts the thread's CPU time, not the time it waits", "[morph_sim][clock]")
{
  // What the bench's compute columns rely on: a thread that sleeps uses (almost) no CPU, one that computes does.
  const vpMorphThreadCpuClock::time_point t0 = vpMorphThreadCpuClock::now();
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  const double asleep = vpMorphThreadCpuClock::millisecondsSince(t0);
  CHECK(asleep >= 0.0);
  CHECK(asleep < 100.0);
  const auto w0 = std::chrono::steady_clock::now();
  const vpMorphThreadCpuClock::time_point t1 = vpMorphThreadCpuClock::now();
  volatile double sink = 0.0;
  while (std::chrono::steady_clock::now() - w0 < std::chrono::milliseconds(50))
    for (int k = 0; k < 1000; ++k)
      sink = sink + std::sqrt(double(k));
  CHECK(vpMorphThreadCpuClock::millisecondsSince(t1) > 0.0);
  CHECK(vpMorphThreadCpuClock::now() >= t1);
}
