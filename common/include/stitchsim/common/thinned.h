#pragma once
// An evenly thinned sample of a stream of unknown length, for pictures: keeps every item
// until `max_items` are held, then drops every other one and keeps every 2nd (4th, ...) item
// from then on. Memory stays bounded by `max_items`; the items kept are evenly spaced in the
// stream and always include its first.

#include <cstddef>
#include <vector>

namespace stitchsim {

template <typename T>
class Thinned {
 public:
  explicit Thinned(std::size_t max_items) : max_(max_items < 2 ? 2 : max_items) {}

  void Add(const T& item) {
    if (seen_++ % stride_ != 0) return;
    if (items_.size() == max_) {
      for (std::size_t i = 0; 2 * i < items_.size(); ++i) items_[i] = items_[2 * i];
      items_.resize((items_.size() + 1) / 2);
      stride_ *= 2;
      if ((seen_ - 1) % stride_ != 0) return;
    }
    items_.push_back(item);
  }
  const std::vector<T>& Items() const { return items_; }
  std::vector<T>& Items() { return items_; }

 private:
  std::size_t max_;
  std::vector<T> items_;
  std::size_t stride_ = 1, seen_ = 0;
};

}  // namespace stitchsim
