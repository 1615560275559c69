// Plain names: what a name read from a file must be before the program makes it part of a path.
#include "tactile/common/plain_name.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace tactile {
namespace {

using ::testing::HasSubstr;

// The message for `name`, which must be refused.
std::string refusal(const std::string& name) {
  const auto error = plain_name_error("sources[2].name", name);
  EXPECT_TRUE(error.has_value()) << "accepted: " << name;
  return error.value_or("");
}

TEST(PlainName, TakesOneFileNameOfLettersDigitsAndPunctuation) {
  for (const std::string& name :
       std::vector<std::string>{"bump", "bump-truth_2", "lab-6x12", "v1.2", "...", ".hidden", "-x",
                                std::string(kMaxPlainNameBytes, 'n')})
    EXPECT_EQ(plain_name_error("name", name), std::nullopt) << name;
}

TEST(PlainName, RefusesWhatIsNotOneNameNamingTheFieldAndWhy) {
  EXPECT_EQ(refusal("../x"),
            "sources[2].name \"../x\" is not a plain name: it holds '/', a path separator (it "
            "must name one file)");
  EXPECT_THAT(refusal("/etc/passwd"), HasSubstr("it holds '/'"));
  EXPECT_THAT(refusal("a\\b"), HasSubstr("it holds '\\'"));
  EXPECT_THAT(refusal(".."), HasSubstr("\"..\" is not a plain name: '..' is a folder"));
  EXPECT_THAT(refusal("."), HasSubstr("'.' is a folder"));
  EXPECT_THAT(refusal(""), HasSubstr("\"\" is not a plain name: it is empty"));
  EXPECT_THAT(refusal(std::string(kMaxPlainNameBytes + 1, 'n')),
              HasSubstr(": it is 101 bytes long, more than the 100 allowed"));
  EXPECT_THAT(refusal("a b"), HasSubstr("it holds ' ' (only ASCII letters"));
  EXPECT_THAT(refusal("$(touch x)"), HasSubstr("it holds '$'"));
  EXPECT_THAT(refusal("`id`"), HasSubstr("it holds '`'"));
  EXPECT_THAT(refusal("it's"), HasSubstr("it holds '''"));
  EXPECT_THAT(refusal("caf\xc3\xa9"), HasSubstr("\"caf\\xc3\\xa9\" is not a plain name: it holds "
                                                "byte 0xc3"));
}

TEST(PlainName, ShowsControlCharactersEscapedOnOneLine) {
  EXPECT_THAT(refusal("a\nb"), HasSubstr("\"a\\nb\" is not a plain name: it holds a control "
                                         "character"));
  EXPECT_THAT(refusal(std::string("a\0b", 3)), HasSubstr("\"a\\x00b\""));
  EXPECT_THAT(refusal("a\tb\r\x7f"), HasSubstr("\"a\\tb\\r\\x7f\""));
  // A control character is named first, even in a name that is also a path.
  EXPECT_THAT(refusal("../\n"), HasSubstr("control character"));
  // A huge name is shown by its start only.
  const auto long_message = refusal(std::string(100000, 'n'));
  EXPECT_LT(long_message.size(), 400u);
  EXPECT_THAT(long_message, HasSubstr("...\" is not a plain name: it is 100000 bytes long"));
}

}  // namespace
}  // namespace tactile
