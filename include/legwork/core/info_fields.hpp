#pragma once
// A runtime's per-frame figures (its Info struct) as a flat list of
// name -> number or name -> text: the pose message's "info" object in
// `legwork serve` (docs/protocol.md) and lw_avatar_info_field() in the C API
// use the same names, written by each runtime's describe(). Fixed capacity:
// filling it allocates nothing.
#include <array>
#include <cstddef>
#include <cstring>

namespace legwork {

struct InfoFields {
  struct Item {
    const char* key = "";
    double number = 0;
    const char* text = nullptr;  // non-null: a text value (static storage)
  };
  static constexpr int kCapacity = 12;
  std::array<Item, kCapacity> items{};
  int count = 0;
  void add(const char* key, double v) {
    if (count < kCapacity) items[static_cast<std::size_t>(count++)] = {key, v, nullptr};
  }
  void add(const char* key, const char* text) {
    if (count < kCapacity) items[static_cast<std::size_t>(count++)] = {key, 0, text};
  }
  // The field named `key`, or nullptr.
  const Item* find(const char* key) const {
    for (int i = 0; i < count; ++i)
      if (std::strcmp(items[static_cast<std::size_t>(i)].key, key) == 0) return &items[static_cast<std::size_t>(i)];
    return nullptr;
  }
};

// The walking figures of the two leg-driving runtimes (wip, combined).
inline void add_walking(InfoFields& out, bool walking, double speed, double distance, double heading) {
  out.add("walking", walking ? 1.0 : 0.0);
  out.add("speed", speed);
  out.add("distance", distance);
  out.add("heading", heading);
}

}  // namespace legwork
