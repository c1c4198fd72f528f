// The three forms of the course's Phong and Blinn-Phong BRDFs (spec §4). Shared by Phong and BlinnPhong.
#pragma once

namespace kiln {

enum class PhongVariant {
  Original,            // f = kd + ks cos^p / cos(theta_i): no 1/pi, not reciprocal, albedo may exceed 1
  Modified,            // f = kd + ks cos^p: no 1/pi, albedo may exceed 1
  ModifiedNormalized,  // f = kd/pi + ks (p+c)/(c pi) cos^p (c = 2 for Phong, 8 for Blinn-Phong)
};

}  // namespace kiln
