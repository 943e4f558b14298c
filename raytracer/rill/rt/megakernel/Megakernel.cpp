// The megakernel (Megakernel.h): its program and its render loop over samples.
#include "rill/rt/megakernel/Megakernel.h"

#include <chrono>
#include <stdexcept>
#include <vector>

#include "rill/Reduce.h"

namespace rt {

using namespace rill;

Kernel compile_for(const Program& program, const std::string& backend_name, Accuracy a) {
  Backend& be = backend(backend_name);
  if (std::string why = be.unavailable_reason(); !why.empty())
    throw std::runtime_error("backend " + backend_name + " cannot run here: " + why);
  if (!be.supports(a))
    throw std::runtime_error(std::string("backend ") + backend_name + " has no " +
                             accuracy_name(a) + " accuracy mode");
  CompileOptions opt;
  opt.accuracy = a;
  return compile(program, backend_name, opt);
}

Megakernel::Megakernel(DeviceScene& scene) : S_(scene) {
  program_ = capture();
}

Program Megakernel::capture() const {
  const Features& F = S_.F;
  const Shading& sh = S_.shading;
  return rill::program("rill_trace", [&] {
    Output<Float3> out_color("color");
    Output<Float> out_depth("depth");
    Output<Int> out_prim("prim");
    Output<Float3> out_normal("normal");
    Output<Int> out_rays("rays");

    const Float inf = as_float(Int(0x7f800000));
    out_depth = inf;
    out_prim = -1;
    out_normal = Float3(0.0f);

    Ray ray{S_.camera.eye, S_.camera.direction(element_coord()), Float(kBig)};
    Bool ray_active = true;

    Float3 color(0.0f);
    Float weight = 1.0f;  // eq. 5.1: the product of the reflection coefficients so far
    Int depth = 0;
    Int mode = 0;  // 0: camera or secondary ray, 1: shadow ray towards light li
    Int li = 0;
    Int rays = 0, iter = 0;
    Bool finished = false;
    Surface surf;
    Float3 local(0.0f);

    // The ray stack (refraction: the reflected branch waits here).
    std::vector<Ray> stack_ray;
    std::vector<Float> stack_weight;
    std::vector<Int> stack_depth;
    for (int s = 0; s < F.stack; ++s) {
      stack_ray.push_back(Ray{Float3(0.0f), Float3(0.0f), Float(0.0f)});
      stack_weight.emplace_back(0.0f);
      stack_depth.emplace_back(0);
    }
    Int sp = 0;

    // max_iter = 0 skips all tracing: render() uses that for a warm-up launch.
    RILL_IF(max_iter_ > 0) {
      RILL_DO {
        Hit hit{Float(0.0f), Float2(0.0f), Int(-1)};
        if (F.geometry) {
          RILL_IF(ray_active) {
            Bool any_hit = mode == 1;
            hit = S_.intersector.intersect(ray, F.shadows ? &any_hit : nullptr);
            rays += 1;
          }
          RILL_ENDIF;
        } else {
          rays += 1;
        }
        Bool hit_something = hit.id >= 0;
        Bool shade_done = false, path_done = false;
        Int cur_mode = mode;  // the branches below may change mode for the next iteration

        auto shade_hit = [&] {
          surf = sh.surface(ray, hit);
          local = sh.emitted(surf);
          RILL_IF(depth == 0) {  // AOVs of the camera ray
            out_depth = hit.t;
            out_prim = hit.id;
            out_normal = surf.ns;
          }
          RILL_ENDIF;
          if (F.shadows) {
            mode = 1;
            li = 0;
            ray = sh.shadow_ray(li, surf, ray_active);
          } else {
            local += sh.unshadowed_light(surf);
            shade_done = true;
          }
        };
        auto miss = [&] {
          color += weight * sh.background;
          path_done = true;
        };
        RILL_IF(cur_mode == 0) {
          if (F.geometry) {
            RILL_IF(hit_something) {
              shade_hit();
            }
            RILL_ELSE {
              miss();
            }
            RILL_ENDIF;
          } else {
            miss();
          }
        }
        RILL_ENDIF;
        if (F.shadows) {
          RILL_IF(cur_mode == 1) {  // a shadow ray came back
            RILL_IF(ray_active && !hit_something) {
              local += sh.light(li, surf);
            }
            RILL_ENDIF;
            li += 1;
            RILL_IF(li < S_.lights.count) {
              ray = sh.shadow_ray(li, surf, ray_active);
            }
            RILL_ELSE {
              mode = 0;
              shade_done = true;
            }
            RILL_ENDIF;
          }
          RILL_ENDIF;
        }

        RILL_IF(shade_done) {
          Bool go = false;
          Branch second;
          sh.shade(surf, local, color, weight, depth, ray, go, F.stack > 0 ? &second : nullptr);
          if (F.stack > 0) {
            RILL_IF(second.wanted && sp < F.stack) {  // the reflection waits on the stack
              for (int s = 0; s < F.stack; ++s) {
                RILL_IF(sp == s) {
                  stack_ray[static_cast<size_t>(s)] = second.ray;
                  stack_weight[static_cast<size_t>(s)] = second.weight;
                  stack_depth[static_cast<size_t>(s)] = depth;
                }
                RILL_ENDIF;
              }
              sp += 1;
            }
            RILL_ENDIF;
          }
          RILL_IF(go) {
            ray_active = true;
            ray.tmax = kBig;
          }
          RILL_ELSE {
            path_done = true;
          }
          RILL_ENDIF;
        }
        RILL_ENDIF;

        RILL_IF(path_done) {
          if (F.stack > 0) {
            RILL_IF(sp > 0) {
              for (int s = 0; s < F.stack; ++s) {
                RILL_IF(sp == s + 1) {
                  ray.o = stack_ray[static_cast<size_t>(s)].o;
                  ray.d = stack_ray[static_cast<size_t>(s)].d;
                  weight = stack_weight[static_cast<size_t>(s)];
                  depth = stack_depth[static_cast<size_t>(s)];
                }
                RILL_ENDIF;
              }
              sp -= 1;
              ray_active = true;
              ray.tmax = kBig;
            }
            RILL_ELSE {
              finished = true;
            }
            RILL_ENDIF;
          } else {
            finished = true;
          }
        }
        RILL_ENDIF;
        iter += 1;
        finished = finished || iter >= max_iter_;
      }
      RILL_UNTIL(finished);
    }
    RILL_ENDIF;

    out_color = color;
    out_rays = rays;
  });
}

Kernel& Megakernel::kernel(const std::string& backend_name, Accuracy a) {
  const std::string key = backend_name + "/" + accuracy_name(a);
  auto it = kernels_.find(key);
  if (it != kernels_.end()) return it->second;
  return kernels_.emplace(key, compile_for(program_, backend_name, a)).first->second;
}

RenderResult Megakernel::render(const RenderSettings& rs, int width, int height, int depth,
                                int spp) {
  RenderResult r;
  r.backend = rs.backend;
  r.width = width;
  r.height = height;
  const auto t0 = std::chrono::steady_clock::now();
  Kernel& k = kernel(rs.backend, rs.accuracy);
  r.from_cache = k.info().cache_hit || k.info().from_disk_cache;
  add_stages(r, k.info());

  // The loop's iteration limit: every ray of a path (the camera ray or a bounce, its shadow
  // rays, the stacked branches) takes one iteration.
  S_.shading.max_depth.set(depth);
  const int stack_factor = S_.F.stack + 1;
  const int64_t iters =
      int64_t{depth + 1} * (static_cast<int64_t>(S_.light_count) + 1) * stack_factor * 2 + 8;

  Stream<Float3> color(width, height), normal(width, height);
  Stream<Float> dist(width, height);
  Stream<Int> prim(width, height), rays(width, height);
  k.outputs(color, dist, prim, normal, rays);
  // A first launch at this size that traces nothing (max_iter = 0): drivers that finish
  // compiling at the first launch of a size (PoCL, Mesa) do it here, so that the trace time
  // below is tracing alone. The ray count's reduction kernels compile here too.
  const auto warm_key =
      std::make_pair(rs.backend + "/" + accuracy_name(rs.accuracy), int64_t{width} * height);
  if (!warmed_.count(warm_key)) {
    max_iter_.set(0);
    k.execute();
    (void)rill::sum(rays);
    warmed_.insert(warm_key);
  }
  max_iter_.set(static_cast<int32_t>(std::min<int64_t>(iters, 1 << 30)));
  r.compile_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();

  const size_t npix = static_cast<size_t>(width) * static_cast<size_t>(height);
  std::vector<glm::dvec3> sum(spp > 1 ? npix : 0, glm::dvec3(0.0));
  const auto start = std::chrono::steady_clock::now();
  for (int s = 0; s < spp; ++s) {
    S_.camera.offset.set(sample_offset(s));
    k.execute();
    ++r.launches;
    r.rays += rill::sum(rays);  // on the device: only the total comes back
    if (s == 0) {
      r.color = color.download();
      r.depth = dist.download();
      r.prim = prim.download();
      r.normal = normal.download();
      if (spp > 1)
        for (size_t p = 0; p < npix; ++p) sum[p] = glm::dvec3(r.color[p]);
    } else {
      std::vector<glm::vec3> c = color.download();
      for (size_t p = 0; p < npix; ++p) sum[p] += glm::dvec3(c[p]);
    }
  }
  if (spp > 1)
    for (size_t p = 0; p < npix; ++p) r.color[p] = glm::vec3(sum[p] / static_cast<double>(spp));
  r.trace_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace rt
