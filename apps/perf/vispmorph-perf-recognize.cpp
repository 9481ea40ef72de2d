/*!
  \file vispmorph-perf-recognize.cpp
  \brief Micro-benchmark of RIGID recognition: a query against databases of 100 and 1000 templates, the stages it is
  made of, and the exhaustive search it stands for, with their ratios printed at the end.

  Templates: shapes drawn by a fixed seed from every image of both datasets (MPEG-7, Kimia-99; both pools of
  data/pools/split.json: a timing measures no rate), each scaled to 160 px and extracted (vpMorphContourExtractor).
  Queries: views of templates turned by any angle, scaled by 0.8-1.2, blurred (sigma 0.7 px) and noisy (sigma 4
  grey levels), extracted the same way. Single threaded; CPU time. The setup's calibration of each database (all
  cores, wall time: look-alikes among every pair of templates) is reported in the context, as calibrate_100_s and
  calibrate_1000_s.

  \code
  vispmorph-perf-recognize --benchmark_repetitions=3   # all, then the ratio table
  vispmorph-perf-recognize --benchmark_filter=stage    # the stages of one query
  \endcode
*/
#include <benchmark/benchmark.h>

#include "vispmorph-perf-reporter.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <random>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphDatabase.h>
#include <visp3/morph/vpMorphOutlineBlur.h>
#include <visp3/morph/vpMorphRigidCheck.h>
#include <visp3/morph/vpMorphRigidShape.h>

namespace
{
constexpr int kPart = 160;   // a shape's longer side, px: a part of the bench's size (12 cm at 0.5 m: 190 px)
constexpr int kSide = 320;   // image side: the part turned by any angle and scaled by 1.2 stays inside (160 sqrt2 1.2)
constexpr int kQueries = 32; // views cycled through by the benchmarks
constexpr std::size_t kLargest = 1000;

vpMorphContour extract(const cv::Mat &m)
{
  vpImage<unsigned char> I(static_cast<unsigned int>(m.rows), static_cast<unsigned int>(m.cols));
  for (int v = 0; v < m.rows; ++v)
    for (int u = 0; u < m.cols; ++u)
      I[v][u] = m.at<unsigned char>(v, u);
  return vpMorphContourExtractor().extract(I);
}

// A dataset image as a dark shape on a light ground, scaled to kPart px, in the middle of a kSide image.
cv::Mat normalise(const std::string &path)
{
  cv::Mat m = cv::imread(path, cv::IMREAD_GRAYSCALE);
  if (m.empty())
    throw std::runtime_error("cannot read '" + path + "'");
  if (cv::mean(m.row(0))[0] + cv::mean(m.col(0))[0] < 256.0)
    m = 255 - m; // MPEG-7 draws white on black
  const double s = static_cast<double>(kPart) / std::max(m.rows, m.cols);
  cv::Mat r, out(kSide, kSide, CV_8UC1, cv::Scalar(255));
  cv::resize(m, r, cv::Size(), s, s, cv::INTER_AREA);
  r.copyTo(out(cv::Rect((kSide - r.cols) / 2, (kSide - r.rows) / 2, r.cols, r.rows)));
  return out;
}

struct Data
{
  std::vector<cv::Mat> images;
  std::vector<vpMorphContour> templates, queries;
  std::vector<std::size_t> truth; // the template each query views
  vpMorphDatabase db100, db1000;
  double calibrate100 = 0.0, calibrate1000 = 0.0; // the databases' calibration, wall seconds

  Data()
    : db100(vpMorphShapeDistance(vpMorphShapeDistance::RIGID)),
      db1000(vpMorphShapeDistance(vpMorphShapeDistance::RIGID))
  {
    std::ifstream f(VISPMORPH_DATA_DIR "/pools/split.json");
    const nlohmann::json split = nlohmann::json::parse(f);
    std::vector<std::string> paths;
    for (const char *d : {"mpeg7", "kimia99"})
      for (const char *p : {"development", "evaluation"})
        for (const nlohmann::json &c : split.at("datasets").at(d).at(p))
          for (const nlohmann::json &i : split.at("datasets").at(d).at("images").at(c.get<std::string>()))
            paths.push_back(std::string(VISPMORPH_DATASETS_DIR) + "/" + d + "/" + i.get<std::string>());
    std::mt19937 rng(100);
    std::shuffle(paths.begin(), paths.end(), rng);
    for (std::size_t k = 0; k < paths.size() && templates.size() < kLargest; ++k) {
      try {
        cv::Mat m = normalise(paths[k]);
        vpMorphContour c = extract(m);
        images.push_back(m);
        templates.push_back(c);
      } catch (const std::exception &) {
        // an image without an object: not a template
      }
    }
    // Calibrated as a user's would be: the search also compares an acceptable answer's look-alikes.
    for (std::size_t k = 0; k < templates.size(); ++k) {
      const vpMorphTemplate t("t" + std::to_string(k), templates[k]);
      if (k < 100)
        db100.add(t);
      db1000.add(t);
    }
    auto seconds = [](vpMorphDatabase &db) {
      const auto t0 = std::chrono::steady_clock::now();
      db.calibrate(0);
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    };
    calibrate100 = seconds(db100);
    calibrate1000 = seconds(db1000);
    std::uniform_real_distribution<double> turn(-180, 180), scale(0.8, 1.2);
    for (int q = 0; q < kQueries; ++q) {
      const std::size_t k = (static_cast<std::size_t>(q) * 37) % 100; // in both databases
      const cv::Mat &src = images[k];
      cv::Mat M = cv::getRotationMatrix2D(cv::Point2f(kSide / 2.f, kSide / 2.f), turn(rng), scale(rng)), v,
              n(src.size(), CV_32F), g;
      cv::warpAffine(src, v, M, src.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(255));
      cv::GaussianBlur(v, v, cv::Size(0, 0), 0.7);
      cv::RNG noise(static_cast<std::uint64_t>(q + 1));
      noise.fill(n, cv::RNG::NORMAL, 0.0, 4.0);
      v.convertTo(g, CV_32F);
      g += n;
      g.convertTo(v, CV_8U);
      queries.push_back(extract(v));
      truth.push_back(k);
    }
  }
};

const Data &data()
{
  static const Data d;
  return d;
}

void recognizeIn(benchmark::State &state, const vpMorphDatabase &db, bool prune)
{
  std::size_t q = 0, right = 0, n = 0;
  for (auto _ : state) {
    const vpMorphRecognition r = db.recognize(data().queries[q], prune);
    right += r.accepted && r.index == data().truth[q];
    ++n;
    q = (q + 1) % data().queries.size();
  }
  state.counters["right"] = static_cast<double>(right) / static_cast<double>(n);
}

void BM_recognize(benchmark::State &state)
{
  recognizeIn(state, state.range(0) == 100 ? data().db100 : data().db1000, true);
}
void BM_exhaustive(benchmark::State &state)
{
  recognizeIn(state, state.range(0) == 100 ? data().db100 : data().db1000, false);
}

// The stages of one query: preparing the view, the coarse alignment on one template, the exact check of one template
// (its rung of blur prepared before, as in a database in use), and the minimal-work correspondence the recognition
// returns.
void BM_stage_prepare(benchmark::State &state)
{
  std::size_t q = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(vpMorphRigidShape(data().queries[q]));
    q = (q + 1) % data().queries.size();
  }
}
void BM_stage_alignOn(benchmark::State &state)
{
  std::vector<vpMorphRigidShape> q, t;
  for (const vpMorphContour &c : data().queries)
    q.emplace_back(c);
  for (std::size_t k = 0; k < 100; ++k)
    t.emplace_back(data().templates[k]);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(q[i % q.size()].alignOn(t[i % t.size()]).cost);
    ++i;
  }
}
void BM_stage_check(benchmark::State &state)
{
  std::vector<vpMorphRigidShape> q, t;
  std::vector<vpMorphRigidShape::Alignment> a;
  for (std::size_t k = 0; k < data().queries.size(); ++k) {
    q.emplace_back(data().queries[k]);
    t.emplace_back(data().templates[data().truth[k]]);
    a.push_back(q.back().alignOn(t.back()));
    (void)vpMorphRigidCheck::check(q.back(), t.back(), a.back()); // lays the template at the view's blur, once
  }
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(vpMorphRigidCheck::check(q[i], t[i], a[i]).cost);
    i = (i + 1) % q.size();
  }
}
// A rung of a template's blur ladder, prepared once per template and rung (vpMorphRigidShape::atBlur()): its outline
// laid at 1 px of blur and the shape prepared from it.
void BM_stage_blurRung(benchmark::State &state)
{
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(vpMorphRigidShape(vpMorphOutlineBlur::blurredTo(data().templates[k], 1.0)));
    k = (k + 1) % 100;
  }
}
void BM_stage_match(benchmark::State &state)
{
  vpMorphMatcher matcher = data().db100.distance().matcher();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(matcher.match(data().queries[i], data().templates[data().truth[i]]).work());
    i = (i + 1) % data().queries.size();
  }
}

BENCHMARK(BM_recognize)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_exhaustive)->Arg(100)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_stage_prepare)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_stage_alignOn)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_stage_check)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_stage_blurRung)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_stage_match)->Unit(benchmark::kMicrosecond);

// Console output plus, at the end, the query time against the exhaustive search's at 100 templates, same process.
class RatioReporter : public vpMorphPerfReporter
{
public:
  void Finalize() override
  {
    ConsoleReporter::Finalize();
    std::ostream &os = GetOutputStream();
    if (!m_time.count("BM_exhaustive/100"))
      return;
    const double base = m_time["BM_exhaustive/100"];
    os << "\nquery time (CPU, fastest repetition) and its ratio to the exhaustive search at 100 templates\n";
    for (const char *n : {"BM_recognize/100", "BM_recognize/1000"})
      if (m_time.count(n))
        os << std::setw(20) << n << std::fixed << std::setprecision(2) << std::setw(10) << m_time[n] << " ms"
           << std::setw(10) << m_time[n] / base << "\n";
  }
};
} // namespace

int main(int argc, char **argv)
{
  for (const char *d : {"/mpeg7", "/kimia99"})
    if (!std::filesystem::is_directory(std::string(VISPMORPH_DATASETS_DIR) + d)) {
      std::cerr << "vispmorph-perf-recognize: no shape datasets in " VISPMORPH_DATASETS_DIR "\n";
      return 1;
    }
  // Built before any timing: a benchmark run first would time it in its first iteration.
  benchmark::AddCustomContext("calibrate_100_s", std::to_string(data().calibrate100));
  benchmark::AddCustomContext("calibrate_1000_s", std::to_string(data().calibrate1000));
  RatioReporter reporter;
  return vpMorphPerfMain(argc, argv, reporter);
}
