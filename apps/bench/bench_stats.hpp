#pragma once
// What every benchmark reports of repeated measurements: the median (benchmarks quote medians on
// these shared, noisy machines) and the process's peak memory. Clocks: core/timing.hpp.
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace egg::app {

// The median of `values`; NaN when there are none.
inline double median(std::vector<double> values) {
  if (values.empty()) return NAN;
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// Peak resident memory of the process so far, MB.
inline double peakRssMb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux reports kilobytes
}

}  // namespace egg::app
