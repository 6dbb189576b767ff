// Fuzzes the metric expression input (AnalyticMetricField, muparser): any bytes must give an
// InputError or a field whose evaluations are SPD or an InputError — never a crash.
#include "ablmg/core/error.hpp"
#include "ablmg/core/metric_field.hpp"

#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string s(reinterpret_cast<const char*>(data), size);
  // three expressions separated by newlines
  std::string e[3];
  std::size_t k = 0;
  for (char c : s) {
    if (c == '\n' && k < 2)
      ++k;
    else
      e[k] += c;
  }
  for (auto form : {ablmg::AnalyticMetricField::Form::Sizes, ablmg::AnalyticMetricField::Form::Tensor}) {
    try {
      ablmg::AnalyticMetricField f(form, e[0], e[1], e[2], "fuzz");
      for (double x : {-1.0, 0.0, 0.5, 1e6}) try {
          const ablmg::Metric2 m = f.at({x, -x});
          if (!m.isSpd()) __builtin_trap();
        } catch (const ablmg::InputError&) {}
    } catch (const ablmg::InputError&) {}
  }
  return 0;
}
