// Golden check: our libsvm models (WEKA's conventions, svm_model.hpp) against WEKA's own SMO
// and SMOreg on the same ARFF training and test sets of simulated perception data.
// Classes must be identical (SMO's defaults on both sides). Regression: at the default KKT
// tolerance of 1e-3 (on the target scaled to [0, 1]) the two solvers stop at different
// near-optimal points (up to ~1 mm apart on these data), so the regression check solves the
// same problem tightly on both sides (tolerance 1e-5) and then allows 0.05 mm, i.e. about 1e-3
// of the 40 mm target range, far under the 1.2 mm RMS error of the paper.

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>

#include "../common/temp_dir.hpp"
#include "tactile/perception/arff.hpp"
#include "tactile/perception/cascade.hpp"
#include "tactile/perception/svm_model.hpp"

namespace perception = tactile::perception;

namespace {

constexpr double kRegressionToleranceMm = 0.05;

std::string run(const std::string& command) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe) throw std::runtime_error("cannot run " + command);
  std::string out;
  std::array<char, 4096> buffer{};
  while (fgets(buffer.data(), buffer.size(), pipe.get())) out += buffer.data();
  return out;
}

// The "predicted" column of WEKA's `-p 0` output (class index or value), one per test row.
std::vector<std::string> weka_predictions(const std::string& classifier, const std::string& train,
                                          const std::string& test) {
  const std::string out = run(std::string(TACTILE_JAVA) + " -Xmx1g -cp " + TACTILE_WEKA_JAR + " " +
                              classifier + " -t " + train + " -T " + test + " -p 0 2>&1");
  std::istringstream in(out);
  std::string line;
  std::vector<std::string> predicted;
  bool table = false;
  while (std::getline(in, line)) {
    if (line.find("inst#") != std::string::npos) {
      table = true;
      continue;
    }
    if (!table) continue;
    std::istringstream fields(line);
    std::string inst, actual, pred;
    if (fields >> inst >> actual >> pred) predicted.push_back(pred);
  }
  if (predicted.empty()) throw std::runtime_error("WEKA gave no predictions:\n" + out);
  return predicted;
}

std::string fmt_name(const std::string& what, int k, const std::string& part) {
  return what + "_" + std::to_string(k) + "_" + part + ".arff";
}

std::string kernel(int degree) {
  return "-K \"weka.classifiers.functions.supportVector.PolyKernel -C 250007 -E " +
         std::to_string(degree) + ".0\"";
}

class WekaGolden : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    data_ = new perception::PerceptionDataset(perception::simulate_dataset(4, 7));
    split_ = new perception::PerceptionSplit(perception::split_per_block(*data_, 0.25));
    dir_ = new tactile::test::TempDir("suite");
  }
  static void TearDownTestSuite() {
    delete data_;
    delete split_;
    delete dir_;
  }
  static perception::InputSet inputs(const std::string& name) {
    for (const auto& s : perception::table2_input_sets(*data_))
      if (s.name == name) return s;
    throw std::runtime_error("no input set " + name);
  }
  static perception::PerceptionDataset* data_;
  static perception::PerceptionSplit* split_;
  static tactile::test::TempDir* dir_;
};
perception::PerceptionDataset* WekaGolden::data_ = nullptr;
perception::PerceptionSplit* WekaGolden::split_ = nullptr;
tactile::test::TempDir* WekaGolden::dir_ = nullptr;

}  // namespace

class WekaSmo : public WekaGolden,
                public ::testing::WithParamInterface<std::pair<const char*, int>> {};

TEST_P(WekaSmo, SameClassesAsWekaSmo) {
  const auto [set_name, degree] = GetParam();
  const auto set = inputs(set_name);
  const auto train = *dir_ / fmt_name(set_name, degree, "train");
  const auto test = *dir_ / fmt_name(set_name, degree, "test");
  perception::write_arff(train, *data_, split_->train, set.columns,
                         perception::ArffTarget::curvature);
  perception::write_arff(test, *data_, split_->test, set.columns,
                         perception::ArffTarget::curvature);
  const auto weka = weka_predictions(
      "weka.classifiers.functions.SMO -C 1.0 -L 0.001 -P 1.0E-12 -N 0 -V -1 -W 1 " + kernel(degree),
      train.string(), test.string());

  std::vector<int> labels;
  for (auto i : split_->train) labels.push_back(data_->samples[i].curvature);
  perception::SvmOptions o;
  o.degree = degree;
  const auto model = perception::SvmModel::train_classifier(
      perception::select_rows(*data_, split_->train, set.columns), labels, o);
  const auto rows = perception::select_rows(*data_, split_->test, set.columns);
  ASSERT_EQ(weka.size(), rows.size());
  int same = 0;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const int ours = static_cast<int>(model.predict(rows[k]));
    const int theirs = std::stoi(weka[k].substr(0, weka[k].find(':'))) - 1;
    same += ours == theirs;
    EXPECT_EQ(ours, theirs) << "test row " << k;
  }
  std::printf("SMO %s exponent %d: %d/%zu predictions identical\n", set_name, degree, same,
              rows.size());
}

INSTANTIATE_TEST_SUITE_P(Table2, WekaSmo,
                         ::testing::Values(std::pair{"all", 1}, std::pair{"all", 2},
                                           std::pair{"dp", 1}, std::pair{"static", 2}));

class WekaSmoReg : public WekaGolden, public ::testing::WithParamInterface<int> {};

TEST_P(WekaSmoReg, FootprintWithinToleranceOfWekaSmoReg) {
  const int curvature = GetParam();
  const auto set = inputs("all");
  std::vector<std::size_t> train, test;
  for (auto i : split_->train)
    if (data_->samples[i].curvature == curvature) train.push_back(i);
  for (auto i : split_->test)
    if (data_->samples[i].curvature == curvature) test.push_back(i);
  const auto train_path = *dir_ / fmt_name("reg", curvature, "train");
  const auto test_path = *dir_ / fmt_name("reg", curvature, "test");
  perception::write_arff(train_path, *data_, train, set.columns, perception::ArffTarget::footprint);
  perception::write_arff(test_path, *data_, test, set.columns, perception::ArffTarget::footprint);
  const auto weka = weka_predictions(
      "weka.classifiers.functions.SMOreg -C 1.0 -N 0 -I "
      "\"weka.classifiers.functions.supportVector.RegSMOImproved -L 0.001 -W 1 -P 1.0E-12 -T "
      "0.00001 -V\" " +
          kernel(1),
      train_path.string(), test_path.string());

  std::vector<double> target;
  for (auto i : train) target.push_back(data_->samples[i].footprint_mm);
  perception::SvmOptions tight;
  tight.tolerance = 1e-5;
  const auto model = perception::SvmModel::train_regressor(
      perception::select_rows(*data_, train, set.columns), target, tight);
  const auto rows = perception::select_rows(*data_, test, set.columns);
  ASSERT_EQ(weka.size(), rows.size());
  double worst = 0;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const double ours = model.predict(rows[k]);
    const double theirs = std::stod(weka[k]);
    worst = std::max(worst, std::abs(ours - theirs));
    EXPECT_NEAR(ours, theirs, kRegressionToleranceMm) << "test row " << k;
  }
  std::printf("SMOreg curvature %d: largest difference %.4f mm over %zu predictions\n", curvature,
              worst, rows.size());
}

INSTANTIATE_TEST_SUITE_P(Curvatures, WekaSmoReg, ::testing::Values(0, 1, 2));
