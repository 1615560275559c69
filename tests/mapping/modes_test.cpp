// Mapping modes: each enum's names round-trip, and an unknown name is refused with the names
// that would have been accepted, since that message is all a user of a file or flag sees.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "tactile/mapping/map.hpp"
#include "tactile/mapping/profile.hpp"

namespace tactile::mapping {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

template <typename Parse>
std::string refusal(Parse parse, const std::string& name) {
  try {
    parse(name);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  ADD_FAILURE() << "'" << name << "' was accepted";
  return {};
}

TEST(MappingModes, NamesRoundTrip) {
  for (const auto m : kMappingMethods) EXPECT_EQ(parse_mapping_method(to_string(m)), m);
  for (const auto n : kNormalisations) EXPECT_EQ(parse_normalisation(to_string(n)), n);
  for (const auto s : kStrainModes) EXPECT_EQ(parse_strain_mode(to_string(s)), s);
  for (const auto s : kProfileShapes) EXPECT_EQ(parse_profile_shape(to_string(s)), s);
}

// The names are part of the file formats (provenance JSON, experiment files): they must not
// drift with the enumerators' spelling.
TEST(MappingModes, NamesAreTheFileFormatsNames) {
  EXPECT_EQ(to_string(MappingMethod::proportional), "proportional");
  EXPECT_EQ(to_string(MappingMethod::integrated), "integrated");
  EXPECT_EQ(to_string(MappingMethod::profile), "profile");
  EXPECT_EQ(to_string(Normalisation::none), "none");
  EXPECT_EQ(to_string(Normalisation::peak), "peak");
  EXPECT_EQ(to_string(Normalisation::p99), "p99");
  EXPECT_EQ(to_string(StrainMode::per_frame), "per-frame");
  EXPECT_EQ(to_string(StrainMode::accumulated), "accumulated");
  EXPECT_EQ(to_string(ProfileShape::bump), "bump");
  EXPECT_EQ(to_string(ProfileShape::hole), "hole");
  EXPECT_EQ(to_string(ProfileShape::flat), "flat");
}

TEST(MappingModes, UnknownNamesAreRefusedWithTheKnownOnes) {
  EXPECT_THAT(refusal(parse_mapping_method, "telepathy"),
              AllOf(HasSubstr("'telepathy'"), HasSubstr("proportional, integrated, profile")));
  EXPECT_THAT(refusal(parse_normalisation, "loud"),
              AllOf(HasSubstr("'loud'"), HasSubstr("none, peak, p99")));
  EXPECT_THAT(refusal(parse_strain_mode, "lagrangian"),
              AllOf(HasSubstr("'lagrangian'"), HasSubstr("per-frame, accumulated")));
  EXPECT_THAT(refusal(parse_profile_shape, "ridge"),
              AllOf(HasSubstr("'ridge'"), HasSubstr("bump, hole, flat")));
  // Names are exact: no case folding, no enumerator spelling.
  refusal(parse_mapping_method, "Profile");
  refusal(parse_strain_mode, "per_frame");
}

}  // namespace
}  // namespace tactile::mapping
