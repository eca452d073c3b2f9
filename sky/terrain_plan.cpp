#include "sky/terrain_plan.h"

#include <string>

namespace firmament {

void addTerrainPasses(const Scene& scene, RenderPlan& plan) {
  const std::string kind = scene.string("/terrain/kind");
  const std::string what = kind == "procedural" ? "procedural (" + scene.string("/terrain/style") + ")" : kind;
  plan.passes.push_back({"terrain/resolve (CPU)",
                         "the height field (" + std::to_string(scene.integer("/terrain/resolution")) +
                             " samples a side), its min/max pyramid and its horizon map (16 azimuths), uploaded",
                         what + " terrain; kept while /terrain and /location are unchanged", false});
  const bool clouds = scene.hasSection("clouds") && !scene.at("/clouds/layers").empty();
  plan.passes.push_back(
      {"terrain/cast_terrain",
       "per pixel: distance to the terrain, normal, sun visibility, cloud optical depth, the share of the sky "
       "the terrain leaves" +
           std::string(clouds ? ", the deck's diffuse light" : ""),
       std::string("the view ray against the height field (min/max pyramid walk), a shadow ray at the sun, the "
                   "horizon map's slices") +
           (clouds ? ", the clouds' Beer shadow map along the sun line and over the hemisphere" : ""),
       true});
  plan.passes.push_back({"terrain/shade_terrain", "the ground's radiance over the sky image (cd/m^2)",
                         "Lambertian ground: sun through the air" + std::string(clouds ? " and the clouds" : "") +
                             ", sky light, the air between camera and ground",
                         true});
}

}  // namespace firmament
