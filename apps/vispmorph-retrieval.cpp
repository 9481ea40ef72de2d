/*!
  \file vispmorph-retrieval.cpp
  \brief Shape retrieval benchmark by morph distance: full distance matrix, MPEG-7 bull's-eye, Kimia-99 ranks.

  \code
  vispmorph-retrieval --images DIR [--classes classes.csv] --out OUTDIR [--model paper|multiscale|polygon|height]
                      [--points N] [--kb K] [--segments M] [--skip C] [--starts K] [--no-mirrors] [--threads T]
                      [--limit N]
  \endcode
  Polygonises the largest object of every image of DIR (all cores), computes the full symmetric matrix of the
  chosen vpMorphShapeDistance (all cores, progress bar on stderr) and writes in OUTDIR:
  - matrix.csv: the distance matrix, one header row and one header column of file names;
  - neighbours.csv: per query, its class and its 40 nearest shapes (itself excluded) with their distances;
  - summary.json and summary.md: bull's-eye score (top-40 recall, itself included), counts at ranks 1..10
    (itself excluded), top-1 accuracy, the wall times and the CPU time of the matrix (all threads); the JSON also
    the commit the tool was built at ("-dirty" with uncommitted changes, "unknown" outside git).
  Classes come from a file,class CSV (--classes, or DIR/classes.csv when present), otherwise from the file name
  up to its last '-' or '_'. Exit status: 0 on success, 1 on an error, 2 on bad arguments.
*/
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include <visp3/core/vpImage.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphShapeDistance.h>

#include "vispmorph-source-commit.h"

namespace fs = std::filesystem;

namespace
{
void usage(std::ostream &os)
{
  os << "Usage: vispmorph-retrieval --images DIR --out OUTDIR [options]\n"
        "  --classes FILE   file,class CSV (default: DIR/classes.csv if present, else the file name up to its\n"
        "                   last '-' or '_')\n"
        "  --model NAME     paper (64 points, mirrors), multiscale (default), polygon or height\n"
        "  --points N       vertices per resampled outline (paper, multiscale, height)\n"
        "  --kb K           bending stiffness of the work model\n"
        "  --cs C           collapse penalty of the work model, in (0, 1]\n"
        "  --scales a,b,..  Gaussian widths (fractions of the perimeter) of the multiscale model\n"
        "  --segments M     descriptor entries of the height model (dividing its points)\n"
        "  --skip C         cost of an unmatched point of the height model\n"
        "  --starts K       starting points the height model's matching tries (0: all)\n"
        "  --no-mirrors     do not match mirror images\n"
        "  --threads T      threads (default: all cores)\n"
        "  --limit N        use only the first N images (quick runs)\n";
}

struct Options
{
  std::string images, classes, out, model = "multiscale", scales;
  long points = 0, threads = 0, limit = 0, segments = 0, starts = -1;
  double kb = -1.0, cs = -1.0, skip = -1.0;
  bool noMirrors = false;
};

bool parse(int argc, char **argv, Options &o)
{
  for (int k = 1; k < argc; ++k) {
    const std::string s = argv[k];
    if (s == "--help" || s == "-h") {
      usage(std::cout);
      std::exit(0);
    } else if (s == "--no-mirrors") {
      o.noMirrors = true;
    } else if (s == "--images" || s == "--classes" || s == "--out" || s == "--model" || s == "--points" ||
               s == "--kb" || s == "--cs" || s == "--threads" || s == "--limit" || s == "--scales" ||
               s == "--segments" || s == "--skip" || s == "--starts") {
      if (k + 1 >= argc) {
        std::cerr << "vispmorph-retrieval: " << s << " needs a value\n";
        return false;
      }
      const std::string v = argv[++k];
      char *end = nullptr;
      if (s == "--images")
        o.images = v;
      else if (s == "--classes")
        o.classes = v;
      else if (s == "--out")
        o.out = v;
      else if (s == "--model")
        o.model = v;
      else if (s == "--scales")
        o.scales = v;
      else if (s == "--kb" || s == "--cs" || s == "--skip") {
        double &x = s == "--kb" ? o.kb : s == "--cs" ? o.cs : o.skip;
        x = std::strtod(v.c_str(), &end);
        if (v.empty() || *end != '\0' || !(x > 0.0)) {
          std::cerr << "vispmorph-retrieval: " << s << " needs a positive number (got '" << v << "')\n";
          return false;
        }
      } else {
        const long x = std::strtol(v.c_str(), &end, 10);
        if (v.empty() || *end != '\0' || x < 0) {
          std::cerr << "vispmorph-retrieval: " << s << " needs a non-negative integer (got '" << v << "')\n";
          return false;
        }
        (s == "--points"     ? o.points
         : s == "--threads"  ? o.threads
         : s == "--segments" ? o.segments
         : s == "--starts"   ? o.starts
                             : o.limit) = x;
      }
    } else {
      std::cerr << "vispmorph-retrieval: unknown option '" << s << "'\n";
      return false;
    }
  }
  if (o.images.empty() || o.out.empty()) {
    std::cerr << "vispmorph-retrieval: --images and --out are required\n";
    return false;
  }
  return true;
}

// Progress bar on stderr, redrawn in place.
vpMorphShapeDistance::Progress bar(const std::string &what)
{
  auto start = std::make_shared<std::chrono::steady_clock::time_point>(std::chrono::steady_clock::now());
  return [what, start](std::size_t done, std::size_t total) {
    const double f = total ? double(done) / double(total) : 1.0;
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - *start).count();
    const int w = 30, fill = static_cast<int>(f * w);
    std::cerr << "\r" << what << " [" << std::string(fill, '#') << std::string(w - fill, ' ') << "] " << std::fixed
              << std::setprecision(1) << 100.0 * f << " % " << done << "/" << total << ", " << std::setprecision(0)
              << el << " s";
    if (f > 0.0 && f < 1.0)
      std::cerr << ", eta " << el * (1.0 - f) / f << " s   ";
    else
      std::cerr << "            ";
    if (done >= total)
      std::cerr << "\n";
    std::cerr.flush();
  };
}

std::string classFromName(const std::string &stem)
{
  const std::size_t p = stem.find_last_of("-_");
  return p == std::string::npos ? stem : stem.substr(0, p);
}

std::map<std::string, std::string> readClasses(const std::string &path)
{
  std::ifstream f(path);
  if (!f)
    throw vpMorphException(vpMorphException::ioError, "cannot read classes file '" + path + "'");
  std::map<std::string, std::string> m;
  std::string line;
  std::size_t n = 0;
  while (std::getline(f, line)) {
    ++n;
    if (!line.empty() && line.back() == '\r')
      line.pop_back();
    if (line.empty())
      continue;
    const std::size_t c = line.find(',');
    if (c == std::string::npos)
      throw vpMorphException(vpMorphException::ioError,
                             "classes file '" + path + "', line " + std::to_string(n) + ": expected file,class");
    const std::string file = line.substr(0, c), cls = line.substr(c + 1);
    if (n == 1 && file == "file")
      continue; // header
    m[file] = cls;
  }
  return m;
}
} // namespace

int main(int argc, char **argv)
{
  Options o;
  if (!parse(argc, argv, o)) {
    usage(std::cerr);
    return 2;
  }
  try {
    vpMorphShapeDistance dist = vpMorphShapeDistance::fromName(o.model);
    if (o.segments > 0 || o.skip > 0.0 || o.starts >= 0 ||
        (o.points > 0 && dist.model() == vpMorphShapeDistance::HEIGHT)) {
      vpMorphHeightFunction h = dist.heightFunction();
      h.setPoints(o.points > 0 ? static_cast<std::size_t>(o.points) : h.getPoints(),
                  o.segments > 0 ? static_cast<std::size_t>(o.segments) : h.getSegments());
      if (o.skip > 0.0)
        h.setSkipCost(o.skip);
      if (o.starts >= 0)
        h.setCandidateStarts(static_cast<std::size_t>(o.starts));
      dist.setHeightFunction(h);
    }
    if (o.points > 0 && dist.model() != vpMorphShapeDistance::HEIGHT)
      dist.setPoints(static_cast<std::size_t>(o.points));
    if (o.kb > 0.0 || o.cs > 0.0)
      dist.setWorkModel(vpMorphWorkModel(dist.workModel().ks(), o.kb > 0.0 ? o.kb : dist.workModel().kb(),
                                         o.cs > 0.0 ? o.cs : dist.workModel().cs()));
    if (o.noMirrors)
      dist.setMirrors(false);
    if (!o.scales.empty()) {
      std::vector<double> sc;
      std::stringstream ss(o.scales);
      std::string t;
      while (std::getline(ss, t, ','))
        sc.push_back(std::atof(t.c_str()));
      dist.setScales(sc);
    }
    const unsigned int threads = static_cast<unsigned int>(o.threads);

    // Images and classes.
    std::error_code ec;
    if (!fs::is_directory(o.images, ec))
      throw vpMorphException(vpMorphException::ioError, "'" + o.images + "' is not a directory");
    std::vector<fs::path> files;
    for (const auto &e : fs::directory_iterator(o.images)) {
      std::string x = e.path().extension().string();
      std::transform(x.begin(), x.end(), x.begin(), ::tolower);
      if (e.is_regular_file() && (x == ".png" || x == ".pgm" || x == ".jpg" || x == ".bmp" || x == ".gif"))
        files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    if (o.limit > 0 && files.size() > static_cast<std::size_t>(o.limit))
      files.resize(static_cast<std::size_t>(o.limit));
    if (files.size() < 2)
      throw vpMorphException(vpMorphException::ioError, "fewer than two images in '" + o.images + "'");
    std::string classesPath = o.classes;
    if (classesPath.empty() && fs::exists(fs::path(o.images) / "classes.csv"))
      classesPath = (fs::path(o.images) / "classes.csv").string();
    std::map<std::string, std::string> classMap;
    if (!classesPath.empty())
      classMap = readClasses(classesPath);
    const std::size_t N = files.size();
    std::vector<std::string> names(N), classes(N);
    for (std::size_t k = 0; k < N; ++k) {
      names[k] = files[k].filename().string();
      if (!classesPath.empty()) {
        auto it = classMap.find(names[k]);
        if (it == classMap.end())
          throw vpMorphException(vpMorphException::notFoundError,
                                 "'" + names[k] + "' has no class in '" + classesPath + "'");
        classes[k] = it->second;
      } else {
        classes[k] = classFromName(files[k].stem().string());
      }
    }

    // Polygons and prepared shapes, on all cores.
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<vpMorphContour> contours(N);
    dist.parallelFor(
        N, threads,
        [&](std::size_t k, vpMorphMatcher &) {
          vpImage<unsigned char> I;
          try {
            vpImageIo::read(I, files[k].string());
          } catch (const vpException &e) {
            throw vpMorphException(vpMorphException::ioError,
                                   "cannot read image '" + files[k].string() + "': " + e.getStringMessage());
          }
          contours[k] = vpMorphContourExtractor().extract(I);
        },
        bar("polygons"));
    const std::vector<vpMorphShapeDistance::Shape> shapes = dist.prepareAll(contours, threads);
    const auto t1 = std::chrono::steady_clock::now();
    // CPU time of the process too: on a shared machine the wall time also measures the other jobs.
    const std::clock_t c1 = std::clock();
    const std::vector<double> D = dist.matrix(shapes, threads, bar("matrix  "));
    const double cpuMatrix = double(std::clock() - c1) / CLOCKS_PER_SEC;
    const auto t2 = std::chrono::steady_clock::now();
    const double secPoly = std::chrono::duration<double>(t1 - t0).count();
    const double secMatrix = std::chrono::duration<double>(t2 - t1).count();

    // Scores. Neighbours are sorted by (distance, index), so ties are broken the same way on every run.
    std::map<std::string, std::size_t> classSize;
    for (const std::string &c : classes)
      ++classSize[c];
    std::vector<std::size_t> rankCounts(10, 0);
    std::size_t bullHits = 0, bullTotal = 0, top1 = 0;
    std::vector<std::vector<std::size_t>> nn(N);
    for (std::size_t i = 0; i < N; ++i) {
      std::vector<std::size_t> order(N);
      for (std::size_t j = 0; j < N; ++j)
        order[j] = j;
      // Itself first (bull's-eye counts it), then by distance.
      std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        if ((a == i) != (b == i))
          return a == i;
        const double da = D[i * N + a], db = D[i * N + b];
        return da < db || (da == db && a < b);
      });
      for (std::size_t r = 0; r < std::min<std::size_t>(40, N); ++r)
        bullHits += classes[order[r]] == classes[i];
      bullTotal += classSize[classes[i]];
      for (std::size_t r = 1; r <= 10 && r < N; ++r)
        rankCounts[r - 1] += classes[order[r]] == classes[i];
      top1 += classes[order[1]] == classes[i];
      nn[i].assign(order.begin() + 1, order.begin() + static_cast<long>(std::min<std::size_t>(41, N)));
    }
    std::size_t rankSum = 0;
    for (std::size_t c : rankCounts)
      rankSum += c;
    const double bullseye = 100.0 * double(bullHits) / double(bullTotal);
    const double top1acc = 100.0 * double(top1) / double(N);

    // Outputs.
    fs::create_directories(o.out);
    {
      std::ofstream f(fs::path(o.out) / "matrix.csv");
      f << "file";
      for (const std::string &n : names)
        f << "," << n;
      f << "\n" << std::setprecision(9);
      for (std::size_t i = 0; i < N; ++i) {
        f << names[i];
        for (std::size_t j = 0; j < N; ++j)
          f << "," << D[i * N + j];
        f << "\n";
      }
    }
    {
      std::ofstream f(fs::path(o.out) / "neighbours.csv");
      f << "query,class,rank,neighbour,neighbour_class,distance\n" << std::setprecision(9);
      for (std::size_t i = 0; i < N; ++i)
        for (std::size_t r = 0; r < nn[i].size(); ++r)
          f << names[i] << "," << classes[i] << "," << r + 1 << "," << names[nn[i][r]] << "," << classes[nn[i][r]]
            << "," << D[i * N + nn[i][r]] << "\n";
    }
    nlohmann::json j;
    j["commit"] = VISPMORPH_SOURCE_COMMIT;
    j["images"] = o.images;
    j["shapes"] = N;
    j["classes"] = classSize.size();
    j["distance"] = nlohmann::json::parse(dist.settingsJson());
    const bool height = dist.model() == vpMorphShapeDistance::HEIGHT;
    j["bullseye_percent"] = bullseye;
    j["rank_counts"] = rankCounts;
    j["rank_counts_sum"] = rankSum;
    j["top1_percent"] = top1acc;
    j["threads"] = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
    j["polygons_seconds"] = secPoly;
    j["matrix_seconds"] = secMatrix;
    j["matrix_cpu_seconds"] = cpuMatrix;
    j["pairs"] = N * (N - 1) / 2;
    std::ofstream(fs::path(o.out) / "summary.json") << j.dump(2) << "\n";
    std::ostringstream md;
    md << std::fixed << std::setprecision(2)
       << "| images | model | shapes | bull's-eye (top-40) | ranks 1..10 (sum) | top-1 | matrix time |\n"
       << "|---|---|---|---|---|---|---|\n"
       << "| " << fs::path(o.images).filename().string() << " | " << dist.name() << " (" << dist.points() << " pts, ";
    if (height)
      md << dist.heightFunction().getSegments() << " segments, skip " << dist.heightFunction().getSkipCost()
         << ", starts " << dist.heightFunction().getCandidateStarts();
    else
      md << "kb " << dist.workModel().kb() << ", cs " << dist.workModel().cs();
    md << (dist.mirrors() ? ", mirrors" : "") << ") | " << N << " | " << bullseye << " % | ";
    for (std::size_t r = 0; r < 10; ++r)
      md << (r ? ", " : "") << rankCounts[r];
    md << " (" << rankSum << ") | " << top1acc << " % | " << std::setprecision(1) << secMatrix << " s ("
       << j["threads"].get<unsigned int>() << " threads; CPU " << cpuMatrix << " s) |\n";
    std::ofstream(fs::path(o.out) / "summary.md") << md.str();
    std::cout << md.str();
  } catch (const vpException &e) {
    std::cerr << "vispmorph-retrieval: " << e.getStringMessage() << std::endl;
    return 1;
  } catch (const std::exception &e) {
    std::cerr << "vispmorph-retrieval: " << e.what() << std::endl;
    return 1;
  }
  return 0;
}
