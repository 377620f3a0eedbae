#include "core/scene3d/scene3d_render.h"

#include <chrono>
#include <cmath>

#include <glm/geometric.hpp>
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include "core/scene3d/pinhole_camera.h"
#include "core/scene3d/scene3d_world.h"
#include "core/scene3d/whitted_tracer.h"

namespace pmsim {

Scene3dImage render_scene3d(const nlohmann::json& scene, const std::string& file) {
  const Scene3dDescription desc = parse_scene3d(scene, file);
  Scene3dImage img = render_scene3d(desc);
  img.settings["scene"] = scene;
  return img;
}

Scene3dImage render_scene3d(const Scene3dDescription& desc) {
  const Scene3dWorld world(desc);
  const WhittedTracer tracer(world);
  const Scene3dCamera& cam = desc.camera;
  const int W = cam.width, H = cam.height;

  const PinholeCamera camera(cam);
  const int n = cam.samples_per_pixel;

  Scene3dImage img;
  img.width = W;
  img.height = H;
  img.rgb_linear.assign(static_cast<std::size_t>(W) * H * 3, 0.0f);
  const auto t0 = std::chrono::steady_clock::now();
  tbb::parallel_for(tbb::blocked_range2d<int>(0, H, 16, 0, W, 16), [&](const tbb::blocked_range2d<int>& r) {
    for (int y = r.rows().begin(); y < r.rows().end(); ++y)
      for (int x = r.cols().begin(); x < r.cols().end(); ++x) {
        glm::dvec3 sum(0.0);
        for (int sy = 0; sy < n; ++sy)
          for (int sx = 0; sx < n; ++sx) {
            const glm::dvec3 d = camera.direction(x + (sx + 0.5) / n, y + (sy + 0.5) / n);
            if (camera.has_filter()) {
              const glm::dvec3 axis = camera.filter_axis(d);
              sum += tracer.trace(cam.position, d, &axis);
            } else {
              sum += tracer.trace(cam.position, d, nullptr);
            }
          }
        sum *= desc.render.exposure / (n * n);
        float* out = &img.rgb_linear[(static_cast<std::size_t>(y) * W + x) * 3];
        for (int c = 0; c < 3; ++c) out[c] = std::isfinite(sum[c]) ? static_cast<float>(sum[c]) : 0.0f;
      }
  });
  img.time_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const Scene3dRenderSettings& rs = desc.render;
  img.settings["type"] = "scene3d";
  img.settings["mode"] = rs.mode == Scene3dMode::Spectral ? "spectral" : "rgb";
  img.settings["channels"] = tracer.channels();
  img.settings["fresnel"] = rs.fresnel == FresnelModel::Exact ? "exact" : "schlick";
  img.settings["tir"] = rs.tir == TirMode::Stop ? "stop" : "split";
  img.settings["max_depth"] = rs.max_depth;
  img.settings["lens_depth"] = rs.lens_depth;
  img.settings["time_ms"] = img.time_ms;
  if (cam.filter_angle_deg) img.settings["filter_angle_deg"] = *cam.filter_angle_deg;
  if (!desc.file.empty()) img.settings["file"] = desc.file;
  return img;
}

}  // namespace pmsim
