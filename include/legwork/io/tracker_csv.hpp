#pragma once
// Tracked points over time as CSV: a header "time,<name>_x,<name>_y,<name>_z,..."
// then one row per sample. Time in seconds, strictly increasing; positions in
// metres in legwork's world frame (y up). Optional quaternion columns
// "<name>_qw,<name>_qx,<name>_qy,<name>_qz" carry an orientation (e.g. the
// headset's). Empty cells or "nan" mark a dropped sample for that point.
#include <legwork/core/types.hpp>

#include <initializer_list>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace legwork::io {

struct TrackedPoint {
  std::string name;
  bool has_rotation = false;
  std::vector<Vec3> position;         // one per sample; NaN where dropped
  std::vector<Quat> rotation;         // only if has_rotation; NaN where dropped
  std::vector<unsigned char> valid;   // 1 if the sample is present and finite
};

struct TrackerTable {
  std::vector<double> time;
  std::vector<TrackedPoint> points;

  int sample_count() const { return static_cast<int>(time.size()); }
  // Point by name; throws legwork::Error listing the names present if absent.
  const TrackedPoint& point(std::string_view name) const;
  bool has(std::string_view name) const;
};

// Errors (legwork::Error) read "file:line:column: message" (column = the
// character column of the offending cell): empty file, missing "time" column,
// a point without all of _x/_y/_z (or with 1-3 of the _q* columns), unknown or
// duplicate columns, non-numeric cells, time not strictly increasing, rows
// with the wrong number of cells. A partly filled sample is dropped whole
// (valid = 0, NaN values). Quaternions are normalised.
TrackerTable parse_tracker_csv(std::string_view text, std::string_view source);
TrackerTable read_tracker_csv(const std::string& path);
std::string format_tracker_csv(const TrackerTable& t);
void write_tracker_csv(const std::string& path, const TrackerTable& t);

}  // namespace legwork::io

#include <legwork/core/tracker.hpp>

namespace legwork::io {

// A table's points as TrackerFrames. Point names (first match wins):
//   head:       head, hmd, headset
//   left hand:  left_hand, left, lhand, left_wrist
//   right hand: right_hand, right, rhand, right_wrist
//   left foot:  left_foot, left_ankle, ankle_l, l_ankle, LeftAnkle, LeftFoot
//   right foot: right_foot, right_ankle, ankle_r, r_ankle, RightAnkle, RightFoot
// Devices absent from the table stay invalid. `need` lists the devices the
// caller requires: a table without one throws legwork::Error naming `source`,
// the device, the accepted names and the points present. Rotation columns are
// required for the head when `need` has it (the head's orientation drives
// every runtime); hands/feet without them get identity rotations.
std::vector<TrackerFrame> frames_from_table(const TrackerTable& table, const std::string& source,
                                            std::initializer_list<Device> need = {});
// The inverse: one point per device valid in any frame, named head,
// left_hand, right_hand, left_foot, right_foot (head with rotation columns).
TrackerTable table_from_frames(std::span<const TrackerFrame> frames);

}  // namespace legwork::io
