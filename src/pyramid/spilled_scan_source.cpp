#include "spilled_scan_source.hpp"

namespace hba::pyramid {

SpilledScanSource::SpilledScanSource(const io::ScanSource& inner)
    : inner_(inner),
      store_(inner.size()),
      state_(new std::atomic<int>[inner.size()]),
      has_intensity_(inner.size(), 0) {
  for (std::size_t i = 0; i < inner.size(); ++i) state_[i].store(kNotKept);
}

PointCloud SpilledScanSource::load(std::size_t i) const {
  if (state_[i].load(std::memory_order_acquire) == kKept) {
    PointCloud cloud = store_.load(i);
    if (!has_intensity_[i]) cloud.intensity.clear();  // the store writes zeros for none
    return cloud;
  }
  PointCloud cloud = inner_.load(i);
  int expected = kNotKept;
  // One thread keeps it; another loading it meanwhile just uses its own.
  if (state_[i].compare_exchange_strong(expected, kKeeping, std::memory_order_acq_rel)) {
    store_.store(i, cloud);
    has_intensity_[i] = cloud.hasIntensity() ? 1 : 0;
    state_[i].store(kKept, std::memory_order_release);
  }
  return cloud;
}

}  // namespace hba::pyramid
