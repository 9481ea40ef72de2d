// vispmorph-reid's shapes and views (vispmorph-reid-views.h).
#include "vispmorph-reid-views.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <random>

#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphRigidCheck.h>
#include <visp3/morph_sim/vpMorphPlanarScene.h>
#include <visp3/morph_sim/vpMorphSilhouetteLayout.h>
#include <visp3/morph_sim/vpMorphThreadCpuClock.h>

namespace fs = std::filesystem;
using nlohmann::json;

namespace
{
constexpr double kObjectSize = 0.12; // longest side, metres: 192 px at the template's 0.5 m, 240 px at 0.4 m
constexpr double kDepth = 0.5;
//! The object's longest side in its texture: the nearest view's (0.4 m), so that every view samples the texture at
//! 1 to 1.5 texels a pixel, which its bilinear rendering integrates as a camera's pixels do instead of aliasing it.
constexpr unsigned int kTexturePixels = 240;

/*
  The image as the scene's texture (vpMorphSilhouetteLayout: a dark object on a light ground, kTexturePixels across,
  anti-aliased). Written once into \e dir.
*/
fs::path texture(const Shape &s, const fs::path &dir)
{
  std::string name = s.id;
  std::replace(name.begin(), name.end(), ':', '-');
  const fs::path path = dir / (name + ".png");
  const vpImage<unsigned char> T =
      vpMorphSilhouetteLayout(vpMorphSilhouetteLayout::read(s.image.string()), kTexturePixels).image();
  // Through a file of its own renamed in place: a failed run leaves no half-written texture.
  const fs::path tmp = dir / (name + ".tmp.png");
  std::error_code ec;
  try {
    vpImageIo::write(T, tmp.string());
  } catch (const vpException &e) {
    throw vpMorphException(vpMorphException::ioError,
                           "cannot write texture '" + path.string() + "': " + e.getStringMessage());
  }
  fs::rename(tmp, path, ec);
  if (ec)
    throw vpMorphException(vpMorphException::ioError, "cannot write texture '" + path.string() + "': " + ec.message());
  return path;
}

//! The shape on the bench's plane, the tag out of view (the extraction takes the largest object).
vpMorphPlanarScene sceneOf(const fs::path &tex)
{
  vpMorphPlanarScene scene(tex.string(), kObjectSize);
  scene.setTagPlacement(0.5, 0.5); // out of view at every pose drawn, and in front of the camera
  return scene;
}

//! The silhouette seen from \e cMo, as the bench sees it: the pieces a card cut apart joined (extractJoined()).
vpMorphContour extract(const vpMorphPlanarScene &scene, const vpHomogeneousMatrix &cMo)
{
  vpImage<unsigned char> I;
  scene.render(cMo, I);
  return vpMorphContourExtractor().extractJoined(I);
}

vpMorphContour teach(const vpMorphPlanarScene &scene)
{
  return extract(scene, vpHomogeneousMatrix(0.0, 0.0, kDepth, 0.0, 0.0, 0.0));
}

//! A query's camera pose and faults under \e condition (see vispmorph-reid.cpp's description).
void drawView(const vpMorphPlanarScene &scene, const std::string &condition, std::uint64_t seed,
              vpHomogeneousMatrix &cMo, vpMorphPlanarScene::Faults &faults)
{
  std::mt19937_64 rng(seed);
  auto uni = [&rng](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  const bool combined = condition.rfind("combined", 0) == 0;
  const double theta = uni(-M_PI, M_PI);
  const double Z = kDepth * (1.0 + uni(-0.2, 0.2));
  const double tilt = condition == "tilt" || combined ? vpMath::rad(uni(0.0, 10.0)) : 0.0;
  const double axis = uni(0.0, 2.0 * M_PI);
  const vpRotationMatrix R = vpRotationMatrix(vpThetaUVector(tilt * std::cos(axis), tilt * std::sin(axis), 0.0)) *
                             vpRotationMatrix(vpThetaUVector(0.0, 0.0, theta));
  cMo = vpHomogeneousMatrix(vpTranslationVector(0.0, 0.0, Z), R);
  for (int attempt = 0; attempt < 100; ++attempt) {
    const vpHomogeneousMatrix M(vpTranslationVector(uni(-0.03, 0.03), uni(-0.03, 0.03), Z), R);
    if (scene.objectInView(M, 5.0)) {
      cMo = M;
      break;
    }
  }
  faults = vpMorphPlanarScene::Faults();
  faults.seed = static_cast<unsigned int>(rng() & 0xffffffffu);
  if (condition == "noise" || combined)
    faults.noiseSigma = uni(2.0, 8.0);
  if (condition == "blur" || combined)
    faults.blurSigma = uni(0.5, 1.5);
  if (condition == "occlusion" || condition == "combined-occlusion") {
    faults.occludedShare = 0.2;
    faults.occluderPosition = uni(0.0, 1.0);
  }
}

} // namespace

std::uint64_t mix(std::uint64_t x)
{
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}
std::uint64_t hashString(const std::string &s)
{
  std::uint64_t h = 1469598103934665603ULL; // FNV-1a
  for (unsigned char ch : s)
    h = (h ^ ch) * 1099511628211ULL;
  return h;
}
std::uint64_t streamSeed(std::uint64_t seed, const std::string &condition, const std::string &shape, std::uint64_t view)
{
  return mix(mix(mix(seed) ^ hashString(condition)) ^ hashString(shape)) ^ mix(view);
}

json readSplit(const std::string &path)
{
  std::ifstream f(path);
  if (!f)
    throw vpMorphException(vpMorphException::ioError, "cannot read the split file '" + path + "'");
  try {
    const json j = json::parse(f);
    (void)j.at("datasets");
    return j;
  } catch (const json::exception &e) {
    throw vpMorphException(vpMorphException::ioError, "malformed split file '" + path + "': " + e.what());
  }
}

std::vector<std::vector<Shape>> poolClasses(const json &split, const std::string &dataset, const std::string &pool,
                                            const fs::path &datasets)
{
  std::vector<std::vector<Shape>> out;
  try {
    const json &d = split.at("datasets").at(dataset);
    for (const json &c : d.at(pool)) {
      const std::string cls = c.get<std::string>();
      std::vector<Shape> shapes;
      for (const json &f : d.at("images").at(cls)) {
        const fs::path image = datasets / dataset / f.get<std::string>();
        if (!fs::exists(image))
          throw vpMorphException(vpMorphException::ioError, "image '" + image.string() + "' not found (is " +
                                                                datasets.string() + " the datasets folder?)");
        shapes.push_back(Shape{dataset + ":" + image.stem().string(), cls, image});
      }
      out.push_back(shapes);
    }
  } catch (const json::exception &e) {
    throw vpMorphException(vpMorphException::ioError,
                           "the split file has no " + dataset + " " + pool + " pool: " + std::string(e.what()));
  }
  return out;
}

vpMorphShapeDistance::Progress every(const std::string &what)
{
  auto last = std::make_shared<std::size_t>(0);
  return [what, last](std::size_t done, std::size_t total) {
    if (done == total || done >= *last + std::max<std::size_t>(1, total / 20)) {
      *last = done;
      std::cerr << what << " " << done << "/" << total << std::endl;
    }
  };
}

std::vector<std::pair<std::string, std::string>> mergeSimilar(std::vector<std::vector<Shape>> &classes,
                                                              unsigned int threads)
{
  std::vector<Shape> all;
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (const std::vector<Shape> &c : classes) {
    const std::size_t first = all.size();
    all.insert(all.end(), c.begin(), c.end());
    for (std::size_t i = first; i < all.size(); ++i)
      for (std::size_t j = i + 1; j < all.size(); ++j)
        pairs.emplace_back(i, j);
  }
  std::vector<vpMorphRigidShape> shapes(all.size());
  std::vector<char> same(pairs.size(), 0);
  const vpMorphShapeDistance runner;
  runner.parallelFor(
      all.size(), threads,
      [&](std::size_t k, vpMorphMatcher &) {
        vpImage<unsigned char> I;
        try {
          vpImageIo::read(I, all[k].image.string());
        } catch (const vpException &e) {
          throw vpMorphException(vpMorphException::ioError,
                                 "cannot read image '" + all[k].image.string() + "': " + e.getStringMessage());
        }
        shapes[k] = vpMorphRigidShape(vpMorphContourExtractor().extract(I));
      },
      every("outlines of the images"));
  runner.parallelFor(
      pairs.size(), threads,
      [&](std::size_t k, vpMorphMatcher &) {
        same[k] =
            vpMorphRigidCheck::similarityDeviation(shapes[pairs[k].first], shapes[pairs[k].second]) <= std::sqrt(2.0);
      },
      every("pairs compared"));
  std::vector<std::size_t> root(all.size());
  for (std::size_t k = 0; k < root.size(); ++k)
    root[k] = k;
  auto find = [&root](std::size_t k) {
    while (root[k] != k)
      k = root[k] = root[root[k]];
    return k;
  };
  for (std::size_t k = 0; k < pairs.size(); ++k)
    if (same[k]) {
      const std::size_t a = find(pairs[k].first), b = find(pairs[k].second);
      root[std::max(a, b)] = std::min(a, b); // the earlier shape stays the group's
    }
  std::vector<std::pair<std::string, std::string>> merged;
  std::size_t k = 0;
  for (std::vector<Shape> &c : classes) {
    std::vector<Shape> kept;
    for (const Shape &s : c) {
      const std::size_t r = find(k++);
      if (all[r].id == s.id)
        kept.push_back(s);
      else
        merged.emplace_back(s.id, all[r].id);
    }
    c = kept;
  }
  return merged;
}

std::vector<Entry> teachAll(const std::vector<Shape> &shapes, const std::vector<bool> &present, const fs::path &texDir,
                            unsigned int threads)
{
  fs::create_directories(texDir);
  std::vector<Entry> entries(shapes.size());
  for (std::size_t k = 0; k < shapes.size(); ++k) { // serially: cheap, and no two threads write one file
    entries[k].shape = shapes[k];
    entries[k].present = present[k];
    entries[k].texture = texture(shapes[k], texDir);
  }
  vpMorphShapeDistance().parallelFor(
      entries.size(), threads,
      [&](std::size_t k, vpMorphMatcher &) { entries[k].taught = teach(sceneOf(entries[k].texture)); },
      every("taught views"));
  return entries;
}

void extractQueries(std::vector<Query> &queries, const std::vector<Entry> &entries, std::uint64_t seed,
                    unsigned int threads)
{
  vpMorphShapeDistance().parallelFor(
      queries.size(), threads,
      [&](std::size_t k, vpMorphMatcher &) {
        Query &q = queries[k];
        const Entry &e = entries[q.entry];
        vpMorphPlanarScene scene = sceneOf(e.texture);
        vpHomogeneousMatrix cMo;
        vpMorphPlanarScene::Faults faults;
        drawView(scene, q.condition, streamSeed(seed, q.condition, e.shape.id, q.view), cMo, faults);
        scene.setFaults(faults);
        try {
          q.contour = extract(scene, cMo);
        } catch (const vpException &) {
          // no object seen: counted as such
        }
      },
      every("views rendered"));
}

void recognizeQueries(std::vector<Query> &queries, const std::vector<Model> &models, unsigned int threads,
                      unsigned int repetitions)
{
  vpMorphShapeDistance().parallelFor(
      queries.size(), threads,
      [&](std::size_t k, vpMorphMatcher &) {
        Query &q = queries[k];
        if (q.contour.empty())
          return;
        for (const Model &model : models)
          for (unsigned int r = 0; r < std::max(1u, repetitions); ++r) {
            const vpMorphThreadCpuClock::time_point t0 = vpMorphThreadCpuClock::now();
            const vpMorphRecognition a = model.recognize(q.contour);
            const double ms = vpMorphThreadCpuClock::millisecondsSince(t0);
            if (r == 0) {
              q.answers.push_back(a);
              q.ms.push_back(ms);
            } else
              q.ms.back() = std::min(q.ms.back(), ms);
          }
      },
      every("queries recognised"));
}
