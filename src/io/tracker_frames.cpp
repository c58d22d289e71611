// Tracker CSV tables <-> the runtimes' TrackerFrame (see tracker_csv.hpp).
#include <legwork/io/tracker_csv.hpp>

#include <array>

namespace legwork::io {
namespace {

using Names = std::initializer_list<const char*>;
const std::array<Names, kDeviceCount> kDeviceNames = {
    Names{"head", "hmd", "headset"},
    Names{"left_hand", "left", "lhand", "left_wrist"},
    Names{"right_hand", "right", "rhand", "right_wrist"},
    Names{"left_foot", "left_ankle", "ankle_l", "l_ankle", "LeftAnkle", "LeftFoot"},
    Names{"right_foot", "right_ankle", "ankle_r", "r_ankle", "RightAnkle", "RightFoot"},
};

const TrackedPoint* find(const TrackerTable& t, Names names) {
  for (const char* n : names)
    if (t.has(n)) return &t.point(n);
  return nullptr;
}

std::string join(Names names) {
  std::string s;
  for (const char* n : names) s += (s.empty() ? "'" : ", '") + std::string(n) + "'";
  return s;
}

}  // namespace

std::vector<TrackerFrame> frames_from_table(const TrackerTable& table, const std::string& source,
                                            std::initializer_list<Device> need) {
  std::array<const TrackedPoint*, kDeviceCount> pts{};
  for (int d = 0; d < kDeviceCount; ++d) pts[static_cast<std::size_t>(d)] = find(table, kDeviceNames[static_cast<std::size_t>(d)]);
  for (Device d : need) {
    const auto i = static_cast<std::size_t>(d);
    if (!pts[i]) {
      std::string present;
      for (const auto& p : table.points) present += (present.empty() ? "" : ", ") + p.name;
      throw Error(source + ": no column for the " + std::string(device_name(d)) + " (accepted point names: " +
                  join(kDeviceNames[i]) + "); points present: " + (present.empty() ? "none" : present));
    }
    if (d == Device::Head && !pts[i]->has_rotation)
      throw Error(source + ": the head needs orientation columns " + pts[i]->name + "_qw, " + pts[i]->name + "_qx, " +
                  pts[i]->name + "_qy, " + pts[i]->name + "_qz");
  }
  std::vector<TrackerFrame> out(static_cast<std::size_t>(table.sample_count()));
  for (std::size_t s = 0; s < out.size(); ++s) {
    out[s].time = table.time[s];
    for (std::size_t d = 0; d < pts.size(); ++d) {
      const TrackedPoint* p = pts[d];
      if (!p) continue;
      auto& dev = out[s].devices[d];
      dev.position = p->position[s];
      dev.rotation = p->has_rotation ? p->rotation[s] : Quat::Identity();
      dev.valid = (s < p->valid.size() ? p->valid[s] != 0 : true) && usable(DevicePose{dev.position, dev.rotation, true});
    }
  }
  return out;
}

TrackerTable table_from_frames(std::span<const TrackerFrame> frames) {
  TrackerTable t;
  std::array<int, kDeviceCount> index{};
  for (int d = 0; d < kDeviceCount; ++d) {
    index[static_cast<std::size_t>(d)] = -1;
    bool any = false;
    for (const auto& f : frames) any = any || f.devices[static_cast<std::size_t>(d)].valid;
    if (!any) continue;
    index[static_cast<std::size_t>(d)] = static_cast<int>(t.points.size());
    TrackedPoint p;
    p.name = *kDeviceNames[static_cast<std::size_t>(d)].begin();
    p.has_rotation = d == static_cast<int>(Device::Head);
    t.points.push_back(std::move(p));
  }
  for (const auto& f : frames) {
    t.time.push_back(f.time);
    for (std::size_t d = 0; d < index.size(); ++d) {
      if (index[d] < 0) continue;
      auto& p = t.points[static_cast<std::size_t>(index[d])];
      const auto& dev = f.devices[d];
      p.position.push_back(dev.position);
      if (p.has_rotation) p.rotation.push_back(dev.rotation);
      p.valid.push_back(dev.valid ? 1 : 0);
    }
  }
  return t;
}

}  // namespace legwork::io
