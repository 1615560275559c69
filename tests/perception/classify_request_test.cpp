// The classify requests' rules, which the command line and the Python module both apply: the
// ranges of C, the folds and the kernel, the contact analysis's trim, a list of input groups by
// name, and the procedure's defaults left to the procedure.

#include "tactile/perception/classify_request.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "../common/error_of.hpp"
#include "../common/temp_dir.hpp"
#include "tactile/perception/recording_inputs.hpp"

namespace {

using tactile::OptionSpelling;
using tactile::RequestError;
using tactile::perception::TrainRequest;
using tactile::test::error_of;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

void set(TrainRequest& r, std::string_view name, const tactile::OptionValue& v,
         OptionSpelling spelling = OptionSpelling::cli) {
  const auto* row = tactile::find_option(tactile::perception::train_options(), name);
  ASSERT_NE(row, nullptr) << name;
  tactile::set_option(r, *row, v, spelling);
}

TEST(ClassifyRequest, UnsetOptionsAreLeftToTheProcedure) {
  const TrainRequest r;
  const auto t = tactile::perception::resolve(r, OptionSpelling::cli);
  EXPECT_EQ(t.procedure, tactile::perception::RecordingProcedure::stroke);
  EXPECT_FALSE(t.trim || t.c || t.kernel_degree || t.baseline_at || t.electrodes);
  EXPECT_TRUE(t.inputs.empty());
  EXPECT_EQ(t.cv_folds, 0);
}

TEST(ClassifyRequest, InputGroupsAreNamesFromTheirTable) {
  TrainRequest r;
  set(r, "inputs", std::string("means,bands"));
  EXPECT_THAT(r.training.inputs, ElementsAre(tactile::perception::InputGroup::means,
                                             tactile::perception::InputGroup::bands));
  EXPECT_THAT(error_of<RequestError>([&] { set(r, "inputs", std::string("means,colour")); }),
              HasSubstr("--inputs: unknown value 'colour' (known: means, rates, hht"));
  EXPECT_THAT(error_of<RequestError>([&] { set(r, "inputs", std::string("")); }),
              HasSubstr("--inputs: is empty"));
}

TEST(ClassifyRequest, RangesAndRulesReadInTheFrontEndsSpelling) {
  TrainRequest r;
  EXPECT_THAT(error_of<RequestError>([&] { set(r, "c", 0.0001); }),
              HasSubstr("--c: 0.0001 is out of range: must be from 0.001 to 100000"));
  EXPECT_THAT(
      error_of<RequestError>([&] { set(r, "cv", std::int64_t{1}, OptionSpelling::python); }),
      HasSubstr("cv: 1 is out of range: must be from 2 to 1000"));
  EXPECT_THAT(error_of<RequestError>([&] { set(r, "kernel_degree", std::int64_t{3}); }),
              HasSubstr("--kernel-degree: 3 is not 1 or 2"));
  // The contact analysis's own rule: 0.5 would leave nothing of the contact.
  EXPECT_THAT(error_of<RequestError>([&] { set(r, "trim", 0.5); }),
              HasSubstr("--trim: trim fraction 0.5 is outside [0, 0.5)"));
  set(r, "cv", std::int64_t{5});
  EXPECT_EQ(tactile::perception::resolve(r, OptionSpelling::cli).cv_folds, 5);
}

TEST(ClassifyRequest, TheInputsAnOutputMustNotNameIncludeEveryRecording) {
  const tactile::test::TempDir dir("classify_inputs");
  std::filesystem::create_directories(dir.path() / "rec" / "sub");
  for (const char* name : {"rec/a.csv", "rec/sub/b.csv"}) {
    std::ofstream(dir.path() / name) << "x\n";
  }
  const auto inputs = tactile::perception::classify_inputs(
      dir.path() / "rec", dir.path() / "labels.csv", {}, OptionSpelling::python);
  ASSERT_EQ(inputs.size(), 3u);
  EXPECT_EQ(inputs[0].option, "labels");
  EXPECT_EQ(inputs[1].option, "recordings");
}

}  // namespace
