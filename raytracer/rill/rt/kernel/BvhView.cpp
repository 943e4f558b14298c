// Uploads the BVH for the kernels (BvhView.h).
#include "rill/rt/kernel/BvhView.h"

#include "rill/rt/kernel/DeviceArrays.h"

namespace rt {

void BvhView::upload(const Bvh& bvh) {
  const size_t n = bvh.nodes.size();
  std::vector<glm::vec3> vlo(n), vhi(n);
  std::vector<glm::ivec4> vlink(n);
  for (size_t i = 0; i < n; ++i) {
    const BvhNode& b = bvh.nodes[i];
    vlo[i] = b.lo;
    vhi[i] = b.hi;
    vlink[i] = glm::ivec4(b.skip, b.first, b.count, 0);
  }
  upload_padded(lo, std::move(vlo));
  upload_padded(hi, std::move(vhi));
  upload_padded(link, std::move(vlink));
  upload_padded(tris, bvh.tris);
  nodes.set(static_cast<int32_t>(n));
}

}  // namespace rt
