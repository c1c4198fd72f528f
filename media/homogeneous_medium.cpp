#include "media/homogeneous_medium.h"

#include "media/describe_util.h"

namespace kiln {

std::string HomogeneousMedium::describe() const {
  std::string d = "homogeneous sigma_a " + describe_rgb(props_.sigma_a) + " sigma_s " + describe_rgb(props_.sigma_s) +
                  " g " + describe_float(phase_.g);
  if (emissive()) d += " Le " + describe_rgb(props_.le);
  return d;
}

}  // namespace kiln
