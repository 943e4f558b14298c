// The accuracy knobs' names (Options.h).
#include "rill/rt/kernel/Options.h"

#include <stdexcept>

namespace rt {

std::string TracerOptions::str() const {
  return std::string(triangle == TriangleTest::Watertight ? "watertight" : "moller") +
         (offset == SelfIntersection::Scaled ? " scaled" : " epsilon") +
         (traversal == Traversal::Recompute ? " recompute" : " incremental");
}

TriangleTest parse_triangle_test(const std::string& s) {
  if (s == "moller") return TriangleTest::MollerTrumbore;
  if (s == "watertight") return TriangleTest::Watertight;
  throw std::invalid_argument("--triangle expects moller or watertight (got '" + s + "')");
}

SelfIntersection parse_self_intersection(const std::string& s) {
  if (s == "epsilon") return SelfIntersection::Epsilon;
  if (s == "scaled") return SelfIntersection::Scaled;
  throw std::invalid_argument("--offset expects epsilon or scaled (got '" + s + "')");
}

Traversal parse_traversal(const std::string& s) {
  if (s == "incremental") return Traversal::Incremental;
  if (s == "recompute") return Traversal::Recompute;
  throw std::invalid_argument("--traversal expects incremental or recompute (got '" + s + "')");
}

Packets parse_packets(const std::string& s) {
  if (s == "auto") return Packets::Auto;
  if (s == "on") return Packets::On;
  if (s == "off") return Packets::Off;
  throw std::invalid_argument("--packets expects auto, on or off (got '" + s + "')");
}

const char* packets_name(Packets p) {
  return p == Packets::On ? "on" : p == Packets::Off ? "off" : "auto";
}

bool packets_for(Packets p, const std::string& backend) {
  (void)backend;  // the rule is the same for every backend today (Options.h says why)
  return p == Packets::On;
}

}  // namespace rt
