#include "hba/sim/world.hpp"

namespace hba::sim {

WorldConfig scenePreset(Scene scene) {
  WorldConfig config;  // mixed
  switch (scene) {
    case Scene::City:
      config.buildings = 70.0;
      config.walls = 25.0;
      config.poles = 40.0;
      config.trees = 6.0;
      config.bushes = 6.0;
      break;
    case Scene::Open:
      config.buildings = 2.0;
      config.walls = 1.0;
      config.poles = 4.0;
      config.trees = 70.0;
      config.bushes = 120.0;
      break;
    case Scene::Indoor:
      config.indoor = true;
      config.max_slope = 0.0;
      config.buildings = config.walls = config.poles = config.trees = config.bushes = 0.0;
      break;
    case Scene::Mixed:
      break;
  }
  return config;
}

}  // namespace hba::sim
