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
  Each model (vpMorphShapeDistance::fromName(), default the database's default; "part+MODEL": vpMorphPartRecognizer
  over MODEL's database, its RIGID twin first) gets a database of the same templates, calibrated, and every query. The
  answer is right (the exact template, accepted), wrong (another, accepted) or rejected; an accepted view of an absent
  shape is a false accept. A rejected view is counted apart when it was rejected as ambiguous
  (vpMorphRecognition::ambiguous: two templates fit it and it does not tell them apart, a look-alike's refusal rather
  than no fit). Query time: the CPU time of recognize() on the thread that runs it (one core). Writes
  DIR/queries.csv (a row per query and model), DIR/summary.md and DIR/summary.json (with the commit the tool was built
  at); the textures drawn (DIR/textures) are kept for a replay.

  --timing: databases of the given sizes, drawn by the seed from every image of both datasets (both pools), each
  queried by --queries views (condition combined) of its own templates on one thread; per model the median and mean
  CPU time per query (each query's fastest of 3 recognitions) and their ratio to the first model's, measured in the
  same run. Writes DIR/timing.md, .json.
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
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <visp3/morph/vpMorphDatabase.h>
#include <visp3/morph/vpMorphException.h>

#include "vispmorph-reid-views.h"
#include "vispmorph-source-commit.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace
{
// --timing: each query recognised this many times, its fastest kept (the noise of a shared machine is one-sided).
constexpr unsigned int kTimingRepetitions = 3;

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
        "default),\n"
        "                    or part+MODEL: vpMorphPartRecognizer, rigid first, then MODEL\n"
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

// The prefix of a model recognised by vpMorphPartRecognizer over the distance that follows it (part+multiscale).
const std::string kPartPrefix = "part+";
bool isPart(const std::string &model) { return model.compare(0, kPartPrefix.size(), kPartPrefix) == 0; }
std::string distanceSpec(const std::string &model) { return isPart(model) ? model.substr(kPartPrefix.size()) : model; }

/*
  A model's distance: a name of vpMorphShapeDistance::fromName(), then settings after colons: "nomirror", "points=N",
  "kb=K", "scales=a/b/c" (e.g. multiscale:nomirror:points=64).
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
    (void)distanceOf(distanceSpec(m)); // unknown names: an error before any work
  return o;
}

std::string outcome(const Query &q, const Entry &e, const Model &tested, std::size_t model)
{
  if (q.contour.empty())
    return "no-silhouette";
  const vpMorphRecognition &r = q.answers[model];
  if (!r.accepted)
    return "rejected";
  if (!e.present)
    return "false-accept";
  return tested.db[r.index].name() == e.shape.id ? "right" : "wrong";
}

//! A view rejected because two templates fit it alike (vpMorphRecognition::ambiguous).
bool lookAlikes(const Query &q, std::size_t model)
{
  return !q.contour.empty() && !q.answers[model].accepted && q.answers[model].ambiguous;
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

std::vector<Model> databases(const std::vector<Entry> &entries, const std::vector<std::string> &models,
                             unsigned int threads)
{
  std::vector<Model> dbs;
  for (const std::string &m : models) {
    Model model{vpMorphDatabase(distanceOf(distanceSpec(m))), nullptr};
    for (const Entry &e : entries)
      if (e.present)
        model.db.add(vpMorphTemplate(e.shape.id, e.taught, e.shape.image.string()));
    model.db.calibrate(threads, every("calibration (" + m + ")"));
    if (isPart(m))
      model.part = std::make_shared<const vpMorphPartRecognizer>(model.db, threads);
    dbs.push_back(std::move(model));
  }
  return dbs;
}

//! \e items ordered by the hash of (seed, key): a draw that depends on nothing but the seed and the names.
template <typename T, typename Key> void shuffleBy(std::vector<T> &items, std::uint64_t seed, Key key)
{
  std::stable_sort(items.begin(), items.end(), [&](const T &a, const T &b) {
    return mix(seed ^ hashString(key(a))) < mix(seed ^ hashString(key(b)));
  });
}

void writeRows(std::ostream &f, const std::vector<Query> &queries, const std::vector<Entry> &entries,
               const std::vector<Model> &dbs, const std::vector<std::string> &models)
{
  f << "model,condition,shape,class,present,view,answer,accepted,outcome,distance,threshold,support,margin,reranked,"
       "ambiguous,evaluated,ms\n"
    << std::setprecision(6);
  for (std::size_t m = 0; m < models.size(); ++m)
    for (const Query &q : queries) {
      const Entry &e = entries[q.entry];
      f << models[m] << ',' << q.condition << ',' << e.shape.id << ',' << e.shape.cls << ',' << e.present << ','
        << q.view << ',';
      if (q.contour.empty()) {
        f << ",0,no-silhouette,,,,,,,,\n";
        continue;
      }
      const vpMorphRecognition &r = q.answers[m];
      f << dbs[m].db[r.index].name() << ',' << r.accepted << ',' << outcome(q, e, dbs[m], m) << ',' << r.distance << ','
        << r.threshold << ',' << r.support << ',' << r.margin << ',' << r.reranked << ',' << r.ambiguous << ','
        << r.evaluated << ',' << q.ms[m] << '\n';
    }
}

//! Per model and condition: right, wrong, rejected and of those the look-alikes' (present shapes), false accepts
//! (absent ones), query time.
json summarise(const std::vector<Query> &queries, const std::vector<Entry> &entries, const std::vector<Model> &dbs,
               const std::vector<std::string> &models, const std::vector<std::string> &conditions, std::ostream &md)
{
  json j = json::array();
  md << "| model | condition | views | right | wrong | rejected | rejected as look-alikes | no silhouette | "
        "absent: views | false accepts |\n"
        "|---|---|---|---|---|---|---|---|---|---|\n";
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
        if (e.present && lookAlikes(q, m))
          ++n["look-alikes"];
        if (!q.contour.empty())
          ms.push_back(q.ms[m]);
      }
      md << "| " << models[m] << " | " << c << " | " << present << " | " << interval(n["right"], present) << " | "
         << interval(n["wrong"], present) << " | " << interval(n["rejected"], present) << " | "
         << interval(n["look-alikes"], present) << " | " << n["no-silhouette"] + n["absent-no-silhouette"] << " | "
         << absent << " | " << interval(n["absent-false-accept"], absent) << " |\n";
      j.push_back({{"model", models[m]},
                   {"condition", c},
                   {"views", present},
                   {"right", n["right"]},
                   {"wrong", n["wrong"]},
                   {"rejected", n["rejected"]},
                   {"rejected_look_alikes", n["look-alikes"]},
                   {"no_silhouette", n["no-silhouette"]},
                   {"absent_views", absent},
                   {"absent_no_silhouette", n["absent-no-silhouette"]},
                   {"false_accepts", n["absent-false-accept"]}});
    }
    timeMd << std::fixed << std::setprecision(2) << "| " << models[m] << " | " << dbs[m].db.size() << " | " << ms.size()
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
  const std::vector<Model> dbs = databases(entries, o.models, threads);
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
     << " classes in the database (" << dbs.front().db.size() << " templates), " << o.absent << " absent ("
     << entries.size() - dbs.front().db.size() << " shapes), " << o.views << " views per shape and condition; "
     << merged.size() << " shapes left out as another's at another size (merged.csv).\n\n";
  const json table = summarise(queries, entries, dbs, o.models, o.conditions, md);
  json j;
  j["commit"] = VISPMORPH_SOURCE_COMMIT;
  j["dataset"] = o.dataset;
  j["pool"] = o.pool;
  j["seed"] = o.seed;
  j["templates"] = dbs.front().db.size();
  j["absent_shapes"] = entries.size() - dbs.front().db.size();
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
     << ", each query's fastest of " << kTimingRepetitions << " recognitions; ratios to " << o.models.front()
     << " in the same run.\n\n"
     << "| templates | model | queries | median ms | mean ms | median ratio | mean ratio "
        "|\n|---|---|---|---|---|---|---|\n";
  json j = json::array();
  for (std::size_t size : o.timing) {
    const std::vector<Entry> entries(teachAllEntries.begin(), teachAllEntries.begin() + static_cast<long>(size));
    const std::vector<Model> dbs = databases(entries, o.models, threads);
    std::vector<Query> queries;
    for (std::size_t k = 0; k < o.queries; ++k) {
      Query q;
      q.entry = static_cast<std::size_t>(mix(o.seed ^ mix(k)) % size);
      q.view = k;
      q.condition = "combined";
      queries.push_back(q);
    }
    extractQueries(queries, entries, o.seed, threads);
    recognizeQueries(queries, dbs, 1, kTimingRepetitions);
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
