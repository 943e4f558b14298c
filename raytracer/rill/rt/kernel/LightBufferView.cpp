// Uploads the light buffer for the kernels, and its lookup (LightBufferView.h).
#include "rill/rt/kernel/LightBufferView.h"

#include "rill/rt/kernel/DeviceArrays.h"

namespace rt {

using namespace rill;

void LightBufferView::upload(const LightBuffer& lb) {
  stats = lb.stats();
  if (!enabled()) return;
  upload_padded(cells, lb.cells);
  upload_padded(tris, lb.tris);
  upload_padded(near, lb.near);
  res.set(lb.res);
  reach.set(lb.reach);
}

Int2 LightBufferView::cell(const Int& light, const Float3& q) const {
  // The major axis (the first of equals), its face, and the other two components over its
  // magnitude: the same float operations as light_buffer_cell on the host.
  Float3 a = abs(q);
  Bool ax = a.x() >= a.y() && a.x() >= a.z();
  Bool ay = !ax && a.y() >= a.z();
  Float w = select(ax, a.x(), select(ay, a.y(), a.z()));
  Float major = select(ax, q.x(), select(ay, q.y(), q.z()));
  Int face = select(ax, Int(0), select(ay, Int(2), Int(4))) + select(major < 0.0f, Int(1), Int(0));
  // Divided, not multiplied by 1 / w: a reciprocal of a huge w is denormal, which some
  // backends flush to zero, while the quotients lie in [-1, 1] (a denormal one adds nothing
  // to 1 below).
  Float w1 = select(w > 0.0f, w, Float(1.0f));
  Float cu = select(ax, q.y(), q.x());
  Float cv = select(ax || ay, q.z(), q.y());
  Float half = to_float(res) * 0.5f;
  Int i = clamp(to_int(floor((cu / w1 + 1.0f) * half)), Int(0), res - 1);
  Int j = clamp(to_int(floor((cv / w1 + 1.0f) * half)), Int(0), res - 1);
  return cells[((light * 6 + face) * res + j) * res + i];
}

}  // namespace rt
