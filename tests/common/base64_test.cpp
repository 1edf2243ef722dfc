// Base64: RFC 4648's test vectors (section 10) and a float array decoded back by hand.
#include "stitchsim/common/base64.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

namespace stitchsim {
namespace {

TEST(Base64Test, Rfc4648Vectors) {
  const std::pair<std::string, std::string> cases[] = {{"", ""},
                                                       {"f", "Zg=="},
                                                       {"fo", "Zm8="},
                                                       {"foo", "Zm9v"},
                                                       {"foob", "Zm9vYg=="},
                                                       {"fooba", "Zm9vYmE="},
                                                       {"foobar", "Zm9vYmFy"}};
  for (const auto& [in, out] : cases) EXPECT_EQ(Base64(in.data(), in.size()), out) << in;
}

TEST(Base64Test, FloatArrayDecodesToTheSameBytes) {
  const std::vector<float> v = {1.0f, -2.5f, 0.1f};
  const std::string text = Base64Of(v);
  ASSERT_EQ(text.size(), 16u);  // 12 bytes -> 16 characters
  // Decode by hand.
  auto value = [](char c) -> int {
    const std::string a = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    return static_cast<int>(a.find(c));
  };
  std::vector<unsigned char> bytes;
  for (std::size_t i = 0; i < text.size(); i += 4) {
    const int n = (value(text[i]) << 18) | (value(text[i + 1]) << 12) | (value(text[i + 2]) << 6) |
                  value(text[i + 3]);
    bytes.push_back(static_cast<unsigned char>(n >> 16));
    bytes.push_back(static_cast<unsigned char>((n >> 8) & 255));
    bytes.push_back(static_cast<unsigned char>(n & 255));
  }
  std::vector<float> back(3);
  std::memcpy(back.data(), bytes.data(), 12);
  EXPECT_EQ(back, v);
}

}  // namespace
}  // namespace stitchsim
