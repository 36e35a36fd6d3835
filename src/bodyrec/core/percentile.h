// Percentiles of timing samples (latency, ms per frame) as bodyrec reports them.
#pragma once

#include <vector>

namespace bodyrec {

// The p-th percentile (0..100) of `values` by nearest rank: the smallest value with at least p % of the
// values at or below it (p95 of 100 sorted values is the 95th). 0 when `values` is empty.
double percentile(std::vector<double> values, double p);

}  // namespace bodyrec
