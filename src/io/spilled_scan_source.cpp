#include "spilled_scan_source.hpp"

namespace hba::io {

SpilledScanSource::SpilledScanSource(const ScanSource& inner)
    : inner_(inner), store_(inner.size()), state_(new std::atomic<int>[inner.size()]) {
  for (std::size_t i = 0; i < inner.size(); ++i) state_[i].store(kNotKept);
}

PointCloud SpilledScanSource::load(std::size_t i) const {
  if (state_[i].load(std::memory_order_acquire) == kKept) return store_.load(i);
  PointCloud cloud = inner_.load(i);
  int expected = kNotKept;
  // One thread keeps it; another loading it meanwhile just uses its own.
  if (state_[i].compare_exchange_strong(expected, kKeeping, std::memory_order_acq_rel)) {
    store_.store(i, cloud);
    state_[i].store(kKept, std::memory_order_release);
  }
  return cloud;
}

}  // namespace hba::io
