#include <cmath>

#include "hba/core/error.hpp"
#include "hba/sim/sensor.hpp"

namespace hba::sim {
namespace {

SensorConfig spinning(SensorModel model, int channels, double lowest, double highest, int columns,
                      double max_range) {
  SensorConfig c;
  c.model = model;
  c.channels = channels;
  c.min_elevation_deg = lowest;
  c.max_elevation_deg = highest;
  c.columns = columns;
  c.max_range = max_range;
  return c;
}

}  // namespace

// Fields of view and resolutions from the makers' data sheets at 10 Hz.
SensorConfig sensorPreset(SensorModel model) {
  switch (model) {
    case SensorModel::Vlp16:
      return spinning(model, 16, -15.0, 15.0, 1800, 100.0);
    case SensorModel::Hdl32:
      return spinning(model, 32, -30.67, 10.67, 2250, 100.0);
    case SensorModel::Hdl64:
      return spinning(model, 64, -24.9, 2.0, 2083, 120.0);
    case SensorModel::Os128:
      return spinning(model, 128, -22.5, 22.5, 1024, 120.0);
    case SensorModel::Livox: {
      SensorConfig c;  // Livox Avia-like: 240 000 points/s, 70.4 deg cone
      c.model = model;
      c.channels = 0;
      c.columns = 0;
      c.points_per_frame = 24000;
      c.field_of_view_deg = 70.4;
      c.max_range = 200.0;
      return c;
    }
  }
  throw Error("unknown sensor model");
}

std::size_t SensorConfig::raysPerFrame() const {
  if (model == SensorModel::Livox) return static_cast<std::size_t>(points_per_frame);
  return static_cast<std::size_t>(channels) * static_cast<std::size_t>(columns);
}

void validate(const SensorConfig& c) {
  if (!(c.range_noise >= 0.0) || c.range_noise > 1.0) {
    throw Error("simulate: range noise must be in [0, 1] m");
  }
  if (!(c.dropout >= 0.0) || c.dropout >= 1.0) throw Error("simulate: dropout must be in [0, 1)");
  if (!(c.min_range >= 0.0) || !(c.max_range > c.min_range) || !std::isfinite(c.max_range)) {
    throw Error("simulate: need 0 <= min range < max range");
  }
  if (c.model == SensorModel::Livox) {
    if (c.points_per_frame <= 0) throw Error("simulate: points per frame must be positive");
    if (!(c.field_of_view_deg > 0.0) || c.field_of_view_deg >= 180.0) {
      throw Error("simulate: the field of view must be in (0, 180) deg");
    }
  } else {
    if (c.channels <= 0 || c.columns <= 0) {
      throw Error("simulate: channels and columns must be positive");
    }
    if (!(c.max_elevation_deg >= c.min_elevation_deg) || c.min_elevation_deg < -90.0 ||
        c.max_elevation_deg > 90.0) {
      throw Error("simulate: the vertical field of view must lie in [-90, 90] deg");
    }
  }
}

}  // namespace hba::sim
