// Prints the volume of a 2 x 3 x 4 m box computed by the installed blockdem library.
#include <iostream>

#include "blockdem/geometry/polyhedron.hpp"

int main() {
  const blockdem::Polyhedron box = blockdem::Polyhedron::box(Eigen::Vector3d(2.0, 3.0, 4.0));
  std::cout << box.volume() << "\n";
  return 0;
}
