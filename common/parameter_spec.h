#pragma once
// One declaration per model parameter. A parameter struct lists its
// parameters once, in an X-macro list of
//   X(type, name, default, unit, min, max, source)
// and generates from that list both its members (RC_PARAMETER_MEMBER) and
// its Fields() visitor (RC_PARAMETER_FIELD), which printing, the JSON
// override file, the range checks and the sensitivity sweep all walk. The
// name is the member's and the JSON key's; min and max bound the valid
// values (inclusive; a choice's are unused); the source says where the
// default comes from ("paper", "artifact: <config line>", "Horowitz", or
// "assumption: <why>").
//
//   #define RC_EXAMPLE_PARAMETERS(X) X(int, sms, 8, "count", 1, 1024, "paper: Vulkan-Sim configuration table")
//   struct Example {
//     RC_EXAMPLE_PARAMETERS(RC_PARAMETER_MEMBER)
//     template <class Self, class Visitor>
//     static void Fields(Self& s, Visitor& v) { RC_EXAMPLE_PARAMETERS(RC_PARAMETER_FIELD) }
//   };
//
// A visitor is called as v(name, field, spec) with the field by reference.
#include <string>

namespace rc {

struct ParameterSpec {
  const char* unit;
  double min;
  double max;
  const char* source;
  bool Contains(double value) const { return value >= min && value <= max; }
};

}  // namespace rc

#define RC_PARAMETER_MEMBER(type, name, value, unit, min, max, source) type name = value;
#define RC_PARAMETER_FIELD(type, name, value, unit, min, max, source) \
  v(#name, s.name, ::rc::ParameterSpec{unit, static_cast<double>(min), static_cast<double>(max), source});
