#pragma once
// Base64 (RFC 4648, with padding) of raw bytes, for binary arrays embedded in JSON (the HTML
// report's typed arrays: little-endian floats and integers, as a browser reads them).

#include <bit>
#include <cstddef>
#include <string>
#include <vector>

namespace stitchsim {

static_assert(std::endian::native == std::endian::little,
              "typed arrays are written in the machine's byte order, which must be little-endian");

std::string Base64(const void* data, std::size_t bytes);

template <typename T>
std::string Base64Of(const std::vector<T>& values) {
  return Base64(values.data(), values.size() * sizeof(T));
}

}  // namespace stitchsim
