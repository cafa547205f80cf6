// io/text_scan.h's line skipping (a frame's index, the split of its rows) against the plain
// definition: a line ends at '\n' or at the end of the text, whose last line may lack it.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "io/text_scan.h"

namespace gs {
namespace {

// Where skipping n lines from `pos` ends, and how many there were, one character at a time.
std::pair<std::size_t, std::size_t> plain_skip(const std::string& text, std::size_t pos,
                                               std::size_t n) {
  std::size_t k = 0;
  while (k < n && pos < text.size()) {
    while (pos < text.size() && text[pos] != '\n') ++pos;
    if (pos < text.size()) ++pos;
    ++k;
  }
  return {pos, k};
}

TEST(TextScan, SkippingLinesMatchesThePlainDefinition) {
  std::mt19937 random(7);
  for (int trial = 0; trial < 300; ++trial) {
    // Lines of 0 to 100 characters (so that newlines fall anywhere in a 32-byte step, several in
    // one or none), with or without the last newline.
    std::string text;
    const int lines = std::uniform_int_distribution<int>(0, 60)(random);
    for (int l = 0; l < lines; ++l) {
      text.append(std::uniform_int_distribution<int>(0, trial % 3 ? 100 : 3)(random), 'x');
      text += '\n';
    }
    if (trial % 2) text.append(std::uniform_int_distribution<int>(0, 40)(random), 'y');
    for (int t = 0; t < 5; ++t) {
      const std::size_t from = plain_skip(text, 0, random() % (lines + 1)).first;
      const std::size_t n = random() % (lines + 3);
      LineCursor c(text, from, 10);
      const auto [pos, k] = plain_skip(text, from, n);
      SCOPED_TRACE("trial " + std::to_string(trial) + ", n " + std::to_string(n));
      EXPECT_EQ(c.skip(n), k);
      EXPECT_EQ(c.pos(), pos);
      EXPECT_EQ(c.line(), 10 + k);
    }
  }
}

}  // namespace
}  // namespace gs
