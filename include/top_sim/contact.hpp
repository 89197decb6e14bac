// Kinematics at the contact and contact faults (physics.md sections 3 and 4).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>

#include "top_sim/model.hpp"

namespace top_sim {

// Velocities at the contact point and the slip parameter (physics.md section 3).
struct ContactKinematics {
  Eigen::Vector3d v_t = Eigen::Vector3d::Zero();    // material velocity of the top at the contact (in-plane)
  Eigen::Vector3d t_hat = Eigen::Vector3d::Zero();  // regularised friction direction
  double rolling_speed = 0.0;                       // R |omega x n|
  double slip = 0.0;                                // s in [0, 1]
};

ContactKinematics contact_kinematics(const Model& model, const Eigen::Vector3d& u, const Eigen::Vector3d& omega);

enum class ContactFault { none, lift_off, painleve, fallen, numerical };

const char* to_string(ContactFault fault);

// Margins whose sign change is a fault: each is > 0 while the contact is valid.
struct ContactMargins {
  double normal_force = 1.0;  // N (lift-off when < 0)
  double painleve = 1.0;      // 1/m - f A, times m (Painleve when <= 0)
  double tilt = 1.0;          // n . f_hat - cos(theta_max) (fallen when < 0)
};

// The first fault the margins show, in the order lift-off, Painleve, fallen.
ContactFault fault_of(const ContactMargins& m);

// One line for the user: what happened and the numbers that show it.
std::string describe(ContactFault fault, const ContactMargins& m, double t);

}  // namespace top_sim
