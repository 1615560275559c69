// The per-footprint accuracy report: counts from hand-built predictions, the CSV's rows and the
// plot's lines.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "../common/temp_dir.hpp"
#include "tactile/perception/report.hpp"

namespace perception = tactile::perception;
namespace fs = std::filesystem;

namespace {

// Predictions whose curvature is right unless listed in `wrong` (indices into `footprints`).
perception::CascadeResult result(const std::string& inputs, int degree,
                                 const std::vector<double>& footprints,
                                 const std::vector<int>& wrong) {
  perception::CascadeResult r;
  r.inputs = inputs;
  r.degree = degree;
  for (std::size_t i = 0; i < footprints.size(); ++i) {
    const bool miss = std::find(wrong.begin(), wrong.end(), int(i)) != wrong.end();
    const int curvature = int(i % 3);
    r.predictions.push_back({curvature, miss ? (curvature + 1) % 3 : curvature, footprints[i], 0});
    r.tested += 1;
    r.correct += miss ? 0 : 1;
  }
  return r;
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST(AccuracyByFootprint, CountsEachSignedFootprintInOrder) {
  // Three 1.25 mm bumps (two wrong), two 1.25 mm pits (one wrong), one 20 mm bump (right).
  const auto r = result("all", 1, {1.25, 20, 1.25, -1.25, 1.25, -1.25}, {0, 2, 3});
  const auto a = perception::accuracy_by_footprint(r);
  ASSERT_EQ(a.size(), 3u);
  EXPECT_EQ(a[0].footprint_mm, -1.25);
  EXPECT_EQ(a[0].tested, 2);
  EXPECT_EQ(a[0].correct, 1);
  EXPECT_EQ(a[1].footprint_mm, 1.25);
  EXPECT_EQ(a[1].tested, 3);
  EXPECT_EQ(a[1].correct, 1);
  EXPECT_EQ(a[2].footprint_mm, 20);
  EXPECT_EQ(a[2].tested, 1);
  EXPECT_EQ(a[2].correct, 1);
  EXPECT_TRUE(perception::accuracy_by_footprint(perception::CascadeResult{}).empty());
}

TEST(AccuracyByFootprint, MisclassifiedLineJoinsBumpsAndPitsWorstShareFirst) {
  // 1.25 mm: 2 bumps + 2 pits, 3 wrong; 2.5 mm: 2 bumps, 1 wrong; 5 mm: 4 pits, 2 wrong;
  // 20 mm: 1 bump, right (not listed). 5 and 2.5 mm tie at half: smaller first.
  const auto r = result("all", 2, {1.25, -1.25, 1.25, -1.25, 2.5, 2.5, -5, -5, -5, -5, 20},
                        {0, 1, 3, 4, 6, 9});
  EXPECT_EQ(perception::misclassified_line(r),
            "all exp 2: curvature wrong on 6 of 11: 1.25 mm 3 of 4, 2.5 mm 1 of 2, 5 mm 2 of 4");
  EXPECT_EQ(perception::misclassified_line(result("dp", 1, {1.25, 20}, {})),
            "dp exp 1: curvature wrong on 0 of 2");
}

TEST(AccuracyByFootprint, WritesOneCsvRowPerFootprintAndOneLinePerInputSet) {
  const tactile::test::TempDir dir_tmp;
  const fs::path& dir = dir_tmp.path();
  std::vector<perception::TimedCascade> rows = {
      {result("all", 1, {1.25, 2.5, -1.25}, {0}), 0},
      {result("dp", 1, {1.25, 2.5, -1.25}, {0, 1}), 0},
      {result("all", 2, {1.25, 2.5, -1.25}, {}), 0},
  };
  perception::write_accuracy_by_footprint_csv(dir / "a.csv", rows);
  const std::string csv = read(dir / "a.csv");
  EXPECT_EQ(count(csv, "\n"), 1u + 9u);  // header + 3 footprints x 3 rows
  EXPECT_NE(csv.find("all,1,1.25,0,1,0.0000\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("dp,1,2.5,0,1,0.0000\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("all,2,-1.25,1,1,1.0000\n"), std::string::npos) << csv;

  const tactile::ChartFiles files =
      perception::write_accuracy_by_footprint_chart(dir / "a1.svg", rows, 1);
  EXPECT_EQ(files.svg, dir / "a1.svg");
  EXPECT_TRUE(fs::is_regular_file(dir / "a1.png"));
  EXPECT_EQ(files.drawn, 6u);  // exponent 1: all and dp, three footprints each
  const std::string svg = read(dir / "a1.svg");
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  EXPECT_NE(svg.find("series: all (2/3); dp (1/3)"), std::string::npos) << svg.substr(0, 600);
  EXPECT_THROW(perception::write_accuracy_by_footprint_chart(dir / "missing" / "x.svg", rows, 1),
               std::runtime_error);
}

// `classify test --csv`: one row per recording, the class names of the model, the value columns
// only when asked for; and the terminal's lines name what each class was taken for.
TEST(ClassifyReport, PredictionsCsvAndConfusionLines) {
  const tactile::test::TempDir dir_tmp;
  const fs::path& dir = dir_tmp.path();
  const std::vector<std::string> names = {"oak", "pine", "felt"};
  perception::LabelledInputs data;
  data.files = {"a.csv", "b.csv", "c.csv"};
  data.rows = {{0.0}, {1.0}, {2.0}};
  data.classes = {0, 1, 1};
  data.values = {1.5, 2.0, 3.0};
  perception::ClassifierTest test;
  test.predictions = {{0, 1.25}, {1, 2.5}, {0, 0.75}};
  test.confusion = {{1, 0, 0}, {1, 1, 0}, {0, 0, 0}};

  perception::write_predictions_csv(dir / "p.csv", names, data, test, false);
  EXPECT_EQ(read(dir / "p.csv"),
            "file,class,predicted,correct\na.csv,oak,oak,1\nb.csv,pine,pine,1\nc.csv,pine,oak,0\n");
  perception::write_predictions_csv(dir / "v.csv", names, data, test, true);
  const std::string with_values = read(dir / "v.csv");
  EXPECT_EQ(with_values.substr(0, with_values.find('\n')),
            "file,class,predicted,correct,value,predicted_value");
  EXPECT_NE(with_values.find("c.csv,pine,oak,0,3,0.75\n"), std::string::npos) << with_values;

  // felt was never tested: no line for it.
  EXPECT_EQ(perception::confusion_lines(names, test.confusion),
            (std::vector<std::string>{"oak: 1/1 correct", "pine: 1/2 correct; taken for oak 1"}));
}
