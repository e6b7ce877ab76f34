// The messages' memory: every byte asked for can be written and read back, on the alignments
// promised, and a growing message keeps its words.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "render/composite/composite_codec.hpp"
#include "render/composite/message_memory.hpp"
#include "render/core/large_array.hpp"

namespace tetray::render {
namespace {

TEST(MessageMemory, HoldsEveryByteOnItsAlignment) {
  for (std::size_t bytes : {std::size_t{1}, std::size_t{4096}, kHugePage - 1, kHugePage,
                            kHugePage + 1, 5 * kHugePage + 12345}) {
    auto* p = static_cast<unsigned char*>(allocate_message(bytes));
    const auto address = reinterpret_cast<std::uintptr_t>(p);
    EXPECT_EQ(address % kCacheLine, 0u) << bytes;
    if (bytes >= kHugePage) {
      EXPECT_EQ(address % kHugePage, 0u) << bytes;
    }
    for (std::size_t k = 0; k < bytes; ++k) p[k] = static_cast<unsigned char>(k * 7 + 1);
    std::size_t wrong = 0;
    for (std::size_t k = 0; k < bytes; ++k) wrong += p[k] != static_cast<unsigned char>(k * 7 + 1);
    EXPECT_EQ(wrong, 0u) << bytes;
    free_message(p, bytes);
  }
}

TEST(MessageMemory, AGrowingMessageKeepsItsWords) {
  PieceMessage message;
  std::vector<std::uint32_t> expected;
  for (std::uint32_t word = 0; word < (3u << 20); ++word) {  // 12 MiB, through several moves
    message.push_back(word * 2654435761u);
    expected.push_back(word * 2654435761u);
  }
  message.resize(message.size() + 5);  // room the encoder then fills
  for (std::size_t k = expected.size(); k < message.size(); ++k) {
    message[k] = 9;
    expected.push_back(9);
  }
  EXPECT_TRUE(std::equal(message.begin(), message.end(), expected.begin(), expected.end()));
}

}  // namespace
}  // namespace tetray::render
