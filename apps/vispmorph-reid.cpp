/*!
  \file vispmorph-reid.cpp
  \brief Re-identification benchmark: is the exact part named, among look-alikes, from a rendered camera view, and is
  a part that is not in the database refused?

  \code
  vispmorph-reid --out DIR [--pool development|evaluation] [--dataset mpeg7|kimia99] [--classes N] [--absent N]
                 [--views N] [--seed S] [--models a,b] [--conditions a,b] [--threads T] [--datasets DIR]
                 [--split FILE]
  vispmorph-reid --timing 100,1000 --out DIR [--queries N] [--seed S] [--models a,b]
  \endcode
  The pool's classes (data/pools/split.json) are shuffled by the seed: the first --classes make the database (every
  image of each, byte-identical ones kept once), the next --absent give the queries of shapes absent from it. Each
  shape is drawn on the bench's plane (vpMorphPlanarScene: dark object, 12 cm long, on a light plane; the tag out of
  view; its texture laid out 240 px long, vpMorphSilhouetteLayout) and its template is the view from 0.5 m, optical axis
  normal to the plane. A query is a view with a uniform turn in [-180, 180) deg, a shift of up to 30 mm either way
  (drawn again until the object is 5 px inside the image), a depth of 0.5 m x (1 + u), u uniform in [-0.2, 0.2], and per
  condition:
  - pose: nothing else;
  - noise: Gaussian noise of sigma uniform in [2, 8] grey levels (object 40, plane 210);
  - blur: Gaussian blur of sigma uniform in [0.5, 1.5] px;
  - tilt: the plane turned about a random axis in it by an angle uniform in [0, 10] deg;
  - combined: noise, blur and tilt together;
  - occlusion: a light-grey card over 20 % of the outline, at a uniform place along it;
  - combined-occlusion: combined with the card.
  Each model (vpMorphShapeDistance::fromName(), default the database's default) gets a database of the same
  templates, calibrated, and every query. The answer is right (the exact template, accepted), wrong (another, accepted)
  or rejected; an accepted view of an absent shape is a false accept. Query time: the CPU time of recognize() on the
  thread that runs it (one core). Writes DIR/queries.csv (a row per query and model), DIR/summary.md and
  DIR/summary.json (with the commit the tool was built at); the textures drawn (DIR/textures) are kept for a replay.

  --timing: databases of the given sizes, drawn by the seed from every image of both datasets (both pools), each
  queried by --queries views (condition combined) of its own templates on one thread; per model the median and mean
  CPU time per query and their ratio to the first model's, measured in the same run. Writes DIR/timing.md, .json.
  Evaluation classes need seeds of 1000 and up, development classes seeds 100-999 (data/pools/README.md).
  Exit status: 0 on success, 1 on an error, 2 on bad arguments.
*/
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <mutex>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphDatabase.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphRigidCheck.h>
#include <visp3/morph_sim/vpMorphPlanarScene.h>
#include <visp3/morph_sim/vpMorphSilhouetteLayout.h>
#include <visp3/morph_sim/vpMorphThreadCpuClock.h>

#include "vispmorph-source-commit.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace
{
struct BadArgs
{
  std::string what;
};

struct Options
{
  std::string out, pool = "development", dataset = "mpeg7", datasets = VISPMORPH_DATASETS_DIR,
                   split = VISPMORPH_DATA_DIR "/pools/split.json";
  std::vector<std::string> models, conditions;
  std::vector<std::size_t> timing;
  unsigned long classes = 5, absent = 5, views = 2, seed = 100, queries = 100, threads = 0;
};

const std::vector<std::string> &conditionNames()
{
  static const std::vector<std::string> names = {
      "pose", "noise", "blur", "tilt", "combined", "occlusion", "combined-occlusion"};
  return names;
}

void usage(std::ostream &os)
{
  os << "Usage: vispmorph-reid --out DIR [options]      (re-identification of rendered views, per condition)\n"
        "       vispmorph-reid --timing 100,1000 --out DIR [--queries N] [--seed S] [--models a,b]\n"
        "  --pool P          development (default; seeds 100-999) or evaluation (seeds >= 1000)\n"
        "  --dataset D       mpeg7 (default) or kimia99\n"
        "  --classes N       classes in the database (default 5; every image of each)\n"
        "  --absent N        further classes whose shapes are queried as absent (default 5)\n"
        "  --views N         views per shape and condition (default 2)\n"
        "  --seed S          classes drawn, views and faults (default 100)\n"
        "  --models a,b      distance models (rigid, polygon, paper, multiscale, height; default: the database's "
        "default)\n"
        "  --conditions a,b  of pose, noise, blur, tilt, combined, occlusion, combined-occlusion (default: all)\n"
        "  --threads T       threads (default: all cores; each query is timed on its own thread)\n"
        "  --queries N       --timing: queries per database (default 100)\n"
        "  --datasets DIR    the shape datasets (default " VISPMORPH_DATASETS_DIR ")\n"
        "  --split FILE      the development/evaluation split (default data/pools/split.json)\n";
}

std::vector<std::string> splitList(const std::string &s)
{
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string t;
  while (std::getline(ss, t, ','))
    if (!t.empty())
      out.push_back(t);
  return out;
}

unsigned long parseUnsigned(const std::string &opt, const std::string &v, unsigned long least)
{
  char *end = nullptr;
  const long long x = std::strtoll(v.c_str(), &end, 10);
  if (v.empty() || *end != '\0' || x < static_cast<long long>(least))
    throw BadArgs{opt + " needs an integer >= " + std::to_string(least) + " (got '" + v + "')"};
  return static_cast<unsigned long>(x);
}

/*
  A model: a name of vpMorphShapeDistance::fromName(), then settings after colons: "nomirror", "points=N", "kb=K",
  "scales=a/b/c" (e.g. multiscale:nomirror:points=64).
*/
vpMorphShapeDistance distanceOf(const std::string &spec)
{
  std::vector<std::string> parts;
  std::stringstream ss(spec);
  std::string t;
  while (std::getline(ss, t, ':'))
    parts.push_back(t);
  if (parts.empty())
    throw BadArgs{"empty model"};
  vpMorphShapeDistance d = vpMorphShapeDistance::fromName(parts[0]);
  for (std::size_t k = 1; k < parts.size(); ++k) {
    const std::string &p = parts[k];
    const std::size_t eq = p.find('=');
    const std::string key = p.substr(0, eq), value = eq == std::string::npos ? std::string() : p.substr(eq + 1);
    if (key == "nomirror")
      d.setMirrors(false);
    else if (key == "points")
      d.setPoints(std::stoul(value));
    else if (key == "kb")
      d.setWorkModel(vpMorphWorkModel(d.workModel().ks(), std::stod(value), d.workModel().cs()));
    else if (key == "scales") {
      std::vector<double> sc;
      std::stringstream vs(value);
      while (std::getline(vs, t, '/'))
        sc.push_back(std::stod(t));
      d.setScales(sc);
    } else
      throw BadArgs{"unknown model setting '" + p + "' in '" + spec + "'"};
  }
  return d;
}

Options parse(int argc, char **argv)
{
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      usage(std::cout);
      std::exit(0);
    }
    if (i + 1 >= argc)
      throw BadArgs{a.rfind("--", 0) == 0 ? "option " + a + " needs a value" : "unknown argument '" + a + "'"};
    const std::string v = argv[++i];
    if (a == "--out")
      o.out = v;
    else if (a == "--pool")
      o.pool = v;
    else if (a == "--dataset")
      o.dataset = v;
    else if (a == "--datasets")
      o.datasets = v;
    else if (a == "--split")
      o.split = v;
    else if (a == "--models")
      o.models = splitList(v);
    else if (a == "--conditions")
      o.conditions = splitList(v);
    else if (a == "--classes")
      o.classes = parseUnsigned(a, v, 1);
    else if (a == "--absent")
      o.absent = parseUnsigned(a, v, 0);
    else if (a == "--views")
      o.views = parseUnsigned(a, v, 1);
    else if (a == "--seed")
      o.seed = parseUnsigned(a, v, 0);
    else if (a == "--queries")
      o.queries = parseUnsigned(a, v, 1);
    else if (a == "--threads")
      o.threads = parseUnsigned(a, v, 0);
    else if (a == "--timing") {
      for (const std::string &s : splitList(v))
        o.timing.push_back(parseUnsigned(a, s, 2));
      if (o.timing.empty())
        throw BadArgs{"--timing needs database sizes (e.g. 100,1000)"};
    } else
      throw BadArgs{"unknown option '" + a + "'"};
  }
  if (o.out.empty())
    throw BadArgs{"--out is required"};
  if (o.pool != "development" && o.pool != "evaluation")
    throw BadArgs{"--pool is development or evaluation (got '" + o.pool + "')"};
  if (o.dataset != "mpeg7" && o.dataset != "kimia99")
    throw BadArgs{"--dataset is mpeg7 or kimia99 (got '" + o.dataset + "')"};
  if (o.timing.empty()) { // the split's seed rule (data/pools/README.md); timing measures no rate
    if (o.pool == "evaluation" && o.seed < 1000)
      throw BadArgs{"the evaluation pool is run with seeds of 1000 and up"};
    if (o.pool == "development" && (o.seed < 100 || o.seed > 999))
      throw BadArgs{"the development pool is run with seeds 100-999"};
  }
  if (o.conditions.empty())
    o.conditions = conditionNames();
  for (const std::string &c : o.conditions)
    if (std::find(conditionNames().begin(), conditionNames().end(), c) == conditionNames().end())
      throw BadArgs{"unknown condition '" + c + "'"};
  if (o.models.empty())
    o.models.push_back(vpMorphDatabase().distance().name());
  for (const std::string &m : o.models)
    (void)distanceOf(m); // unknown names: an error before any work
  return o;
}

// A deterministic stream per (seed, condition, shape, view), whatever the threads: splitmix64 over the keys.
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

//! One shape of a dataset: its identifier (dataset:file stem), class and image.
struct Shape
{
  std::string id, cls;
  fs::path image;
};

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

//! The classes of a pool of a dataset, in the split's order, each with its images (duplicates already left out).
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

//! A query's camera pose and faults under \e condition (see the file's description).
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

//! A shape of the run: its texture, its taught view, and whether its template is in the database.
struct Entry
{
  Shape shape;
  fs::path texture;
  vpMorphContour taught;
  bool present = true;
};

//! One query (a view of one shape under one condition) and each model's answer.
struct Query
{
  std::size_t entry = 0, view = 0;
  std::string condition;
  vpMorphContour contour; // empty when no object was seen
  std::vector<vpMorphRecognition> answers;
  std::vector<double> ms; // CPU time of recognize(), per model
};

std::string outcome(const Query &q, const Entry &e, const vpMorphDatabase &db, std::size_t model)
{
  if (q.contour.empty())
    return "no-silhouette";
  const vpMorphRecognition &r = q.answers[model];
  if (!r.accepted)
    return "rejected";
  if (!e.present)
    return "false-accept";
  return db[r.index].name() == e.shape.id ? "right" : "wrong";
}

//! Wilson's 95 % interval of a proportion k / n, in percent.
std::string interval(std::size_t k, std::size_t n)
{
  if (n == 0)
    return "-";
  const double z = 1.96, p = double(k) / double(n), d = 1.0 + z * z / n;
  const double c = (p + z * z / (2.0 * n)) / d, h = z * std::sqrt(p * (1.0 - p) / n + z * z / (4.0 * n * n)) / d;
  std::ostringstream os;
  os << std::fixed << std::setprecision(2) << 100.0 * p << " % [" << 100.0 * std::max(0.0, c - h) << ", "
     << 100.0 * std::min(1.0, c + h) << "]";
  return os.str();
}

double quantile(std::vector<double> v, double q)
{
  if (v.empty())
    return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(std::min<double>(v.size() - 1, std::floor(q * v.size())))];
}

double mean(const std::vector<double> &v)
{
  double s = 0.0;
  for (double x : v)
    s += x;
  return v.empty() ? std::numeric_limits<double>::quiet_NaN() : s / v.size();
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

/*
  Shapes of one class that are one shape at two sizes (or turned): vpMorphRigidCheck::similarityDeviation() of their
  images' outlines within sqrt(2) px of the coarser image (the digitisation bound of two images of one outline). Each
  group keeps its first shape in the split's order; the others are left out of the run and returned (shape, kept).
*/
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

//! The textures and taught views of \e shapes (all cores); \e texDir receives the textures.
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

std::vector<vpMorphDatabase> databases(const std::vector<Entry> &entries, const std::vector<std::string> &models,
                                       unsigned int threads)
{
  std::vector<vpMorphDatabase> dbs;
  for (const std::string &m : models) {
    vpMorphDatabase db(distanceOf(m));
    for (const Entry &e : entries)
      if (e.present)
        db.add(vpMorphTemplate(e.shape.id, e.taught, e.shape.image.string()));
    db.calibrate(threads, every("calibration (" + m + ")"));
    dbs.push_back(std::move(db));
  }
  return dbs;
}

//! Renders and extracts every query's view (all cores); a view without object stays empty.
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

//! Recognises every query with every database on \e threads threads, each recognition timed on its own thread.
void recognizeQueries(std::vector<Query> &queries, const std::vector<vpMorphDatabase> &dbs, unsigned int threads)
{
  vpMorphShapeDistance().parallelFor(
      queries.size(), threads,
      [&](std::size_t k, vpMorphMatcher &) {
        Query &q = queries[k];
        if (q.contour.empty())
          return;
        for (const vpMorphDatabase &db : dbs) {
          const vpMorphThreadCpuClock::time_point t0 = vpMorphThreadCpuClock::now();
          q.answers.push_back(db.recognize(q.contour));
          q.ms.push_back(vpMorphThreadCpuClock::millisecondsSince(t0));
        }
      },
      every("queries recognised"));
}

//! \e items ordered by the hash of (seed, key): a draw that depends on nothing but the seed and the names.
template <typename T, typename Key> void shuffleBy(std::vector<T> &items, std::uint64_t seed, Key key)
{
  std::stable_sort(items.begin(), items.end(), [&](const T &a, const T &b) {
    return mix(seed ^ hashString(key(a))) < mix(seed ^ hashString(key(b)));
  });
}

void writeRows(std::ostream &f, const std::vector<Query> &queries, const std::vector<Entry> &entries,
               const std::vector<vpMorphDatabase> &dbs, const std::vector<std::string> &models)
{
  f << "model,condition,shape,class,present,view,answer,accepted,outcome,distance,threshold,support,margin,reranked,"
       "evaluated,ms\n"
    << std::setprecision(6);
  for (std::size_t m = 0; m < models.size(); ++m)
    for (const Query &q : queries) {
      const Entry &e = entries[q.entry];
      f << models[m] << ',' << q.condition << ',' << e.shape.id << ',' << e.shape.cls << ',' << e.present << ','
        << q.view << ',';
      if (q.contour.empty()) {
        f << ",0,no-silhouette,,,,,,,\n";
        continue;
      }
      const vpMorphRecognition &r = q.answers[m];
      f << dbs[m][r.index].name() << ',' << r.accepted << ',' << outcome(q, e, dbs[m], m) << ',' << r.distance << ','
        << r.threshold << ',' << r.support << ',' << r.margin << ',' << r.reranked << ',' << r.evaluated << ','
        << q.ms[m] << '\n';
    }
}

//! Per model and condition: right, wrong, rejected (present shapes), false accepts (absent ones), query time.
json summarise(const std::vector<Query> &queries, const std::vector<Entry> &entries,
               const std::vector<vpMorphDatabase> &dbs, const std::vector<std::string> &models,
               const std::vector<std::string> &conditions, std::ostream &md)
{
  json j = json::array();
  md << "| model | condition | views | right | wrong | rejected | no silhouette | absent: views | false accepts |\n"
        "|---|---|---|---|---|---|---|---|---|\n";
  std::ostringstream timeMd;
  timeMd << "\n| model | templates | queries | median ms | mean ms | 95th percentile ms |\n|---|---|---|---|---|---|\n";
  for (std::size_t m = 0; m < models.size(); ++m) {
    std::vector<double> ms;
    for (const std::string &c : conditions) {
      std::map<std::string, std::size_t> n;
      std::size_t present = 0, absent = 0;
      for (const Query &q : queries) {
        if (q.condition != c)
          continue;
        const Entry &e = entries[q.entry];
        ++(e.present ? present : absent);
        ++n[(e.present ? "" : "absent-") + outcome(q, e, dbs[m], m)];
        if (!q.contour.empty())
          ms.push_back(q.ms[m]);
      }
      md << "| " << models[m] << " | " << c << " | " << present << " | " << interval(n["right"], present) << " | "
         << interval(n["wrong"], present) << " | " << interval(n["rejected"], present) << " | "
         << n["no-silhouette"] + n["absent-no-silhouette"] << " | " << absent << " | "
         << interval(n["absent-false-accept"], absent) << " |\n";
      j.push_back({{"model", models[m]},
                   {"condition", c},
                   {"views", present},
                   {"right", n["right"]},
                   {"wrong", n["wrong"]},
                   {"rejected", n["rejected"]},
                   {"no_silhouette", n["no-silhouette"]},
                   {"absent_views", absent},
                   {"absent_no_silhouette", n["absent-no-silhouette"]},
                   {"false_accepts", n["absent-false-accept"]}});
    }
    timeMd << std::fixed << std::setprecision(2) << "| " << models[m] << " | " << dbs[m].size() << " | " << ms.size()
           << " | " << quantile(ms, 0.5) << " | " << mean(ms) << " | " << quantile(ms, 0.95) << " |\n";
  }
  md << timeMd.str();
  return j;
}

/*!
  Writes each (file name, text) of \e files into \e dir, every one to a temporary file first and all renamed in place
  only once all are written: an error leaves none of them half-written, nor a mix of two runs' results.
*/
void writeResults(const fs::path &dir, const std::vector<std::pair<std::string, std::string>> &files)
{
  std::vector<fs::path> written;
  auto discard = [&written] {
    std::error_code ec;
    for (const fs::path &p : written)
      fs::remove(p, ec);
  };
  for (const auto &f : files) {
    written.push_back(dir / ("." + f.first + ".tmp"));
    std::ofstream out(written.back(), std::ios::binary | std::ios::trunc);
    out << f.second;
    out.close();
    if (!out) {
      discard();
      throw vpMorphException(vpMorphException::ioError, "cannot write '" + written.back().string() + "'");
    }
  }
  for (std::size_t k = 0; k < files.size(); ++k) {
    std::error_code ec;
    fs::rename(written[k], dir / files[k].first, ec);
    if (ec) {
      discard();
      throw vpMorphException(vpMorphException::ioError,
                             "cannot write '" + (dir / files[k].first).string() + "': " + ec.message());
    }
  }
}

int reid(const Options &o)
{
  const json split = readSplit(o.split);
  std::vector<std::vector<Shape>> classes = poolClasses(split, o.dataset, o.pool, o.datasets);
  if (o.classes + o.absent > classes.size())
    throw vpMorphException(vpMorphException::badParameterError, "the " + o.dataset + " " + o.pool + " pool has " +
                                                                    std::to_string(classes.size()) +
                                                                    " classes, fewer than --classes + --absent");
  shuffleBy(classes, o.seed, [](const std::vector<Shape> &c) { return c.front().cls; });
  classes.resize(o.classes + o.absent);
  fs::create_directories(o.out); // once the inputs are known to be there
  const unsigned int threads = static_cast<unsigned int>(o.threads);
  const std::vector<std::pair<std::string, std::string>> merged = mergeSimilar(classes, threads);
  std::ostringstream mergedCsv;
  mergedCsv << "shape,same_as\n";
  for (const auto &m : merged)
    mergedCsv << m.first << ',' << m.second << '\n';
  std::vector<Shape> shapes;
  std::vector<bool> present;
  for (std::size_t k = 0; k < o.classes + o.absent; ++k)
    for (const Shape &s : classes[k]) {
      shapes.push_back(s);
      present.push_back(k < o.classes);
    }
  const std::vector<Entry> entries = teachAll(shapes, present, fs::path(o.out) / "textures", threads);
  const std::vector<vpMorphDatabase> dbs = databases(entries, o.models, threads);
  std::vector<Query> queries;
  for (const std::string &c : o.conditions)
    for (std::size_t e = 0; e < entries.size(); ++e)
      for (std::size_t v = 0; v < o.views; ++v) {
        Query q;
        q.entry = e;
        q.view = v;
        q.condition = c;
        queries.push_back(q);
      }
  extractQueries(queries, entries, o.seed, threads);
  recognizeQueries(queries, dbs, threads);

  std::ostringstream rows;
  writeRows(rows, queries, entries, dbs, o.models);
  std::ostringstream md;
  md << "Re-identification: " << o.dataset << " " << o.pool << " pool, seed " << o.seed << ", " << o.classes
     << " classes in the database (" << dbs.front().size() << " templates), " << o.absent << " absent ("
     << entries.size() - dbs.front().size() << " shapes), " << o.views << " views per shape and condition; "
     << merged.size() << " shapes left out as another's at another size (merged.csv).\n\n";
  const json table = summarise(queries, entries, dbs, o.models, o.conditions, md);
  json j;
  j["commit"] = VISPMORPH_SOURCE_COMMIT;
  j["dataset"] = o.dataset;
  j["pool"] = o.pool;
  j["seed"] = o.seed;
  j["templates"] = dbs.front().size();
  j["absent_shapes"] = entries.size() - dbs.front().size();
  j["views_per_shape"] = o.views;
  j["merged_shapes"] = merged.size();
  j["results"] = table;
  writeResults(o.out, {{"merged.csv", mergedCsv.str()},
                       {"queries.csv", rows.str()},
                       {"summary.json", j.dump(1) + "\n"},
                       {"summary.md", md.str()}});
  std::cout << md.str();
  return 0;
}

int timing(const Options &o)
{
  const json split = readSplit(o.split);
  std::vector<Shape> all;
  for (const char *d : {"mpeg7", "kimia99"})
    for (const char *p : {"development", "evaluation"})
      for (const std::vector<Shape> &c : poolClasses(split, d, p, o.datasets))
        all.insert(all.end(), c.begin(), c.end());
  shuffleBy(all, o.seed, [](const Shape &s) { return s.id; });
  const std::size_t largest = *std::max_element(o.timing.begin(), o.timing.end());
  if (largest > all.size())
    throw vpMorphException(vpMorphException::badParameterError, "the datasets hold " + std::to_string(all.size()) +
                                                                    " distinct shapes, fewer than " +
                                                                    std::to_string(largest));
  all.resize(largest);
  fs::create_directories(o.out);
  const unsigned int threads = static_cast<unsigned int>(o.threads);
  const std::vector<Entry> teachAllEntries =
      teachAll(all, std::vector<bool>(all.size(), true), fs::path(o.out) / "textures", threads);
  std::ostringstream md;
  md << "Query time on one thread (CPU time of recognize()), views under the combined condition, seed " << o.seed
     << "; ratios to " << o.models.front() << " in the same run.\n\n"
     << "| templates | model | queries | median ms | mean ms | median ratio | mean ratio "
        "|\n|---|---|---|---|---|---|---|\n";
  json j = json::array();
  for (std::size_t size : o.timing) {
    const std::vector<Entry> entries(teachAllEntries.begin(), teachAllEntries.begin() + static_cast<long>(size));
    const std::vector<vpMorphDatabase> dbs = databases(entries, o.models, threads);
    std::vector<Query> queries;
    for (std::size_t k = 0; k < o.queries; ++k) {
      Query q;
      q.entry = static_cast<std::size_t>(mix(o.seed ^ mix(k)) % size);
      q.view = k;
      q.condition = "combined";
      queries.push_back(q);
    }
    extractQueries(queries, entries, o.seed, threads);
    recognizeQueries(queries, dbs, 1);
    std::vector<double> base;
    for (std::size_t m = 0; m < o.models.size(); ++m) {
      std::vector<double> ms;
      for (const Query &q : queries)
        if (!q.contour.empty())
          ms.push_back(q.ms[m]);
      if (m == 0)
        base = ms;
      md << std::fixed << std::setprecision(2) << "| " << size << " | " << o.models[m] << " | " << ms.size() << " | "
         << quantile(ms, 0.5) << " | " << mean(ms) << " | " << quantile(ms, 0.5) / quantile(base, 0.5) << " | "
         << mean(ms) / mean(base) << " |\n";
      j.push_back({{"templates", size},
                   {"model", o.models[m]},
                   {"queries", ms.size()},
                   {"median_ms", quantile(ms, 0.5)},
                   {"mean_ms", mean(ms)}});
    }
  }
  writeResults(o.out, {{"timing.json", j.dump(1) + "\n"}, {"timing.md", md.str()}});
  std::cout << md.str();
  return 0;
}
} // namespace

int main(int argc, char **argv)
{
  Options o;
  try {
    o = parse(argc, argv);
  } catch (const BadArgs &e) {
    std::cerr << "vispmorph-reid: " << e.what << "\n";
    usage(std::cerr);
    return 2;
  } catch (const vpException &e) {
    std::cerr << "vispmorph-reid: " << e.getStringMessage() << "\n";
    return 2;
  }
  try {
    return o.timing.empty() ? reid(o) : timing(o);
  } catch (const vpException &e) {
    std::cerr << "vispmorph-reid: " << e.getStringMessage() << std::endl;
  } catch (const std::exception &e) {
    std::cerr << "vispmorph-reid: " << e.what() << std::endl;
  }
  return 1;
}
