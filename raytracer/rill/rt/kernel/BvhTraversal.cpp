// The intersector's walk over the moving triangles' BVH (Intersector.h, accel/Bvh.h).
//
// The nodes are in depth-first order with a skip index each, so the walk needs no stack: a
// box the ray enters (before the best hit so far) leads to the next node, its first child or,
// after a leaf, the next subtree; a box it misses leads to its skip. Every triangle whose box
// the ray enters is tested, in the tree's order; the hit kept is the closest by
// test_primitive's rule whatever that order is. The loop visits each node at most once, so it
// ends on any input: the node index only grows.
#include "rill/rt/kernel/Intersector.h"

namespace rt {

using namespace rill;

void Intersector::walk_bvh(const Float3& o, const RaySteps& r, const Bool& any_hit,
                           Hit& best) const {
  const Float3& d = r.d;
  Int node = 0;
  RILL_WHILE(node < bvh_.nodes && !(any_hit && best.id >= 0)) {
    const Float3 lo = bvh_.lo[node];
    const Float3 hi = bvh_.hi[node];
    const Int4 link = bvh_.link[node];  // (skip, first, count, 0)
    // The slab test of ray_box, against this node's (padded) box and up to the best hit.
    Float3 t0 = (lo - o) * r.inv;
    Float3 t1 = (hi - o) * r.inv;
    Float3 tn = select(r.flat, Float3(-kBig), min(t0, t1));
    Float3 tf = select(r.flat, Float3(kBig), max(t0, t1));
    Bool outside = any(r.flat && ((o < lo) || (o > hi)));
    Float t_in = max(max(tn.x(), tn.y()), max(tn.z(), 0.0f));
    Float t_out = min(min(tf.x(), tf.y()), min(tf.z(), best.t));
    RILL_IF(!outside && t_in <= t_out) {
      RILL_FOR(Int k = 0, k < link.z(), k += 1) {
        test_primitive(o, d, bvh_.tris[link.y() + k], best);
        RILL_IF(any_hit && best.id >= 0) {
          RILL_BREAK;
        }
        RILL_ENDIF;
      }
      RILL_ENDFOR;
      node += 1;
    }
    RILL_ELSE {
      node = link.x();
    }
    RILL_ENDIF;
  }
  RILL_ENDWHILE;
}

}  // namespace rt
