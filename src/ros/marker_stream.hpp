// What ~markers sends of one top, and when (docs/ros.md, "Recording"): sized for rosbag and for rviz's CPU.
// - the fixed markers (plane, grid, body, stripe, stem, tip) when their colour, shape or grid pitch changed, and
//   again every `refresh` seconds (a late rviz or a bag recorded from any moment has them within that time);
// - the moving markers (spin and velocity arrows, label) when they look different (0.1 mm, other text), and the
//   trail's open chunk at every marker tick;
// - each closed chunk of the trail once when it closes or changes, a DELETE when it goes, and every closed chunk
//   again within `refresh` seconds, a few per tick.
// A new subscriber gets everything at the next tick.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <ros/time.h>
#include <visualization_msgs/MarkerArray.h>

#include "conversions.hpp"
#include "markers.hpp"
#include "trail.hpp"
#include "top_sim/model.hpp"
#include "top_sim/snapshot.hpp"

namespace top_sim_ros {

struct MarkerTick {
  ros::Time stamp;
  double wall = 0.0;     // [s] the node's wall clock
  double period = 0.0;   // [s] between marker ticks
  double refresh = 0.0;  // [s] every marker is sent again at least this often
};

class MarkerStream {
 public:
  // This tick's markers of one top, their namespaces prefixed by `prefix`, appended to `out`.
  void collect(const top_sim::Snapshot& s, const top_sim::Top& top, const Trail& trail, const Frames& frames,
               const MarkerStyle& style, const std::string& prefix, const MarkerTick& tick,
               visualization_msgs::MarkerArray& out);
  // A DELETE for every marker of the top (a killed top).
  void remove_all(const top_sim::Snapshot& s, const top_sim::Top& top, const Frames& frames, const MarkerStyle& style,
                  const std::string& prefix, const ros::Time& stamp, visualization_msgs::MarkerArray& out);
  void resend_all();  // a new subscriber: everything goes out at the next tick
  // The body's contact shapes (model.shapes), drawn in place of the ordinary top when active; fixed for the top's
  // life (no command changes them), so set once where the top's simulator is made.
  void set_shapes(const top_sim::ShapeSet& shapes) { shapes_ = shapes; }

  // The grid's pitch, coarser as the contact point moves faster (grid_pitch_for); the grid's tf frame uses it.
  double grid_pitch() const { return pitch_; }
  void follow_speed(double speed, double base) { pitch_ = grid_pitch_for(speed, base, pitch_ > 0.0 ? pitch_ : base); }

 private:
  struct FixedKey {
    Rgb colour{0.0f, 0.0f, 0.0f};
    double pitch = 0.0, mass = 0.0, inertia = 0.0, radius = 0.0, offset = 0.0;
    std::uint32_t touching = 0;  // a body with shapes: the touching ones, and which side a lone rim is drawn on
    bool rim_up = false;
    bool operator==(const FixedKey& o) const {
      return colour == o.colour && pitch == o.pitch && mass == o.mass && inertia == o.inertia &&
             radius == o.radius && offset == o.offset && touching == o.touching && rim_up == o.rim_up;
    }
  };
  void collect_moving(const top_sim::Snapshot& s, const top_sim::Top& top, const Frames& frames,
                      const MarkerStyle& style, const std::string& prefix, const MarkerTick& tick,
                      visualization_msgs::MarkerArray& out);
  void collect_trail(const Trail& trail, const Frames& frames, const std::string& prefix, const MarkerTick& tick,
                     visualization_msgs::MarkerArray& out);

  double pitch_ = 0.0;  // set by follow_speed before the first tick (StateOutput::open)
  top_sim::ShapeSet shapes_;  // none active: the ordinary top
  FixedKey fixed_sent_;
  double fixed_wall_ = -std::numeric_limits<double>::infinity();
  std::vector<visualization_msgs::Marker> moving_sent_;  // the arrows and label as last sent
  double moving_wall_ = -std::numeric_limits<double>::infinity();
  std::vector<std::pair<std::uint64_t, std::uint64_t>> chunks_sent_;  // (id, version) of closed chunks, by id
  std::uint64_t refresh_from_ = 0;  // the id the round of refreshed chunks goes on from
  double refresh_credit_ = 0.0;     // chunks due for their refresh, fraction included
  bool head_sent_ = false;
};

}  // namespace top_sim_ros
