// The benchmark's objects (vpMorphBenchObjectSet): any folder or list of silhouettes laid out, bad images skipped
// with their reason, deformed variants supplied or generated, and the pools of the shape datasets.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph_bench/vpMorphBenchObjectSet.h>

namespace fs = std::filesystem;

namespace
{
const std::string kData = VISPMORPH_DATA_DIR;

//! A folder with two usable silhouettes (a white-on-black MPEG-7-like one, a tool with its drawn deformed variant)
//! and three unusable images: unreadable, uniform, empty.
std::string makeFolder()
{
  const fs::path dir = fs::current_path() / "objects-in";
  fs::remove_all(dir);
  fs::create_directories(dir);
  vpImage<unsigned char> blob(200, 240, 0);
  for (unsigned int i = 40; i < 160; ++i)
    for (unsigned int j = 30; j < 210; ++j)
      if ((i - 100.0) * (i - 100.0) / 3600 + (j - 120.0) * (j - 120.0) / 8100 < 1.0)
        blob[i][j] = 255;
  vpImageIo::write(blob, (dir / "blob.png").string());
  fs::copy_file(kData + "/objects/key.png", dir / "key.png");
  fs::copy_file(kData + "/objects/key-deformed.png", dir / "key-deformed.png");
  std::ofstream(dir / "garbled.png") << "this is not a PNG";
  vpImageIo::write(vpImage<unsigned char>(100, 100, 200), (dir / "uniform.png").string());
  std::ofstream(dir / "empty.png");
  return dir.string();
}
} // namespace

TEST_CASE("bench objects: a folder laid out, bad images skipped with their reason", "[bench][objects]")
{
  const std::string dir = makeFolder();
  const std::vector<vpMorphBenchObjectSet::Source> sources = vpMorphBenchObjectSet::listImages(dir);
  std::vector<std::string> names;
  for (const auto &s : sources)
    names.push_back(s.name);
  CHECK(names == std::vector<std::string>{"blob", "empty", "garbled", "key", "uniform"}); // key-deformed goes with key
  const vpMorphBenchObjectSet set = vpMorphBenchObjectSet::images(sources, "objects-out", 100);
  CHECK(set.names() == std::vector<std::string>{"blob", "key"});
  REQUIRE(set.skipped().size() == 3);
  for (const auto &k : set.skipped())
    INFO(k.source << ": " << k.reason);
  // Every used object has a laid-out template, a deformed variant and a rough one, all with one object.
  for (const vpMorphBenchObjectSet::Object &o : set.objects()) {
    for (const std::string &f : {o.image, o.deformedImage, o.roughImage}) {
      vpImage<unsigned char> I;
      vpImageIo::read(I, f);
      CHECK(I.getWidth() == 316);
      CHECK_FALSE(vpMorphContourExtractor().extract(I).empty());
    }
  }
  // The key's drawn variant is laid out in its frame, truth by the largest overlap (no mask); the blob's is generated.
  CHECK(set["key"].truth == vpMorphBenchObjectSet::TRUTH_OVERLAP);
  CHECK(set["key"].deformedMask.empty());
  CHECK(set["blob"].truth == vpMorphBenchObjectSet::TRUTH_PART);
  CHECK(set["blob"].undeformedShare >= 0.6);
  CHECK(fs::is_regular_file(set["blob"].deformedMask));
  CHECK_THROWS_AS(set["garbled"], vpMorphException);
  // A list file: relative paths, comments; duplicates named once.
  {
    std::ofstream list(dir + "/list.txt");
    list << "# two objects\nblob.png\n\nkey.png\n" << dir << "/blob.png\n";
  }
  const vpMorphBenchObjectSet fromList =
      vpMorphBenchObjectSet::images(vpMorphBenchObjectSet::listImages(dir + "/list.txt"), "objects-out-list", 100);
  CHECK(fromList.names() == std::vector<std::string>{"blob", "key"});
  REQUIRE(fromList.skipped().size() == 1);
  CHECK(fromList.skipped()[0].reason.find("already named 'blob'") != std::string::npos);
  CHECK_THROWS_AS(vpMorphBenchObjectSet::listImages("/nonexistent/objects"), vpMorphException);
}

TEST_CASE("bench objects: a supplied variant with a mask of its undeformed part holds the truth there",
          "[bench][objects]")
{
  const fs::path dir = fs::current_path() / "objects-mask";
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy_file(kData + "/objects/key.png", dir / "key.png");
  fs::copy_file(kData + "/objects/key-deformed.png", dir / "key-deformed.png");
  fs::copy_file(kData + "/objects/key.png", dir / "key-deformed-mask.png"); // a mask: any dark region will do here
  const vpMorphBenchObjectSet set =
      vpMorphBenchObjectSet::images(vpMorphBenchObjectSet::listImages(dir.string()), "objects-mask-out", 100);
  REQUIRE(set.size() == 1);
  CHECK(set["key"].truth == vpMorphBenchObjectSet::TRUTH_PART);
  CHECK(fs::is_regular_file(set["key"].deformedMask));
}

TEST_CASE("bench objects: the six tools as they are, and a pool's errors", "[bench][objects]")
{
  const vpMorphBenchObjectSet tools = vpMorphBenchObjectSet::tools(kData, "objects-tools");
  CHECK(tools.names() == std::vector<std::string>{"pliers", "wedge", "key", "hammer", "screwdriver", "wrench"});
  CHECK(tools["pliers"].truth == vpMorphBenchObjectSet::TRUTH_ARTICULATED);
  CHECK(tools["key"].image == kData + "/objects/key.png");

  const std::string split = kData + "/pools/split.json", datasets = VISPMORPH_DATASETS_DIR;
  CHECK_THROWS_AS(vpMorphBenchObjectSet::poolImages(split, datasets, "training", 1), vpMorphException);
  CHECK_THROWS_AS(vpMorphBenchObjectSet::poolImages(split, datasets, "development", 0), vpMorphException);
  try {
    vpMorphBenchObjectSet::poolImages(split, "/nonexistent/datasets", "development", 1);
    FAIL("no error");
  } catch (const vpMorphException &e) {
    CHECK(e.getCode() == vpMorphException::notFoundError);
  }
}

// ctest runs the [datasets] tests only where the shape datasets are (else it reports them skipped).
TEST_CASE("bench objects: the pools of the shape datasets", "[bench][objects][datasets]")
{
  const std::string split = kData + "/pools/split.json", datasets = VISPMORPH_DATASETS_DIR;
  if (!fs::is_directory(datasets)) {
    WARN("SKIPPED: the pools' images need the shape datasets (" << datasets << ")");
    return;
  }
  // One image a class of each pool, in the split's order, the same every time; no class in both.
  const auto dev = vpMorphBenchObjectSet::poolImages(split, datasets, "development", 1);
  const auto eval = vpMorphBenchObjectSet::poolImages(split, datasets, "evaluation", 1);
  CHECK(dev.size() == 39); // 35 MPEG-7 classes, 4 Kimia-99 ones
  CHECK(eval.size() == 40);
  const auto again = vpMorphBenchObjectSet::poolImages(split, datasets, "development", 2);
  REQUIRE(again.size() == 2 * dev.size());
  CHECK(again[0].path == dev[0].path); // the first of a class stays first
  CHECK(dev[0].name.rfind("mpeg7-apple-", 0) == 0);
  for (const auto &d : dev) {
    CHECK(fs::is_regular_file(d.path));
    for (const auto &e : eval)
      CHECK(d.name != e.name);
  }
}
