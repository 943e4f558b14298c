// Control-flow programs: if / else-if / else, while, do-until, for, break, continue,
// discard, arrays (1D, 2D, 3D, out-of-range indices), uniforms (changed between launches),
// swizzles and write masks, element_index / element_coord on a 2D stream, lane-group
// operations used so that no output depends on the group.
//
// They compute with integers and with floats whose every intermediate is exact (small
// multiples of 1/4), so every accuracy mode must reproduce the reference interpreter bit for
// bit, together with the number of elements written.
#include <memory>

#include "Suite.h"

namespace rill::conformance {

namespace {

using Gen = std::function<uint32_t(Rng&)>;

Gen ints(int32_t lo, int32_t hi) {
  return [lo, hi](Rng& r) {
    return static_cast<uint32_t>(std::uniform_int_distribution<int32_t>(lo, hi)(r));
  };
}
// Multiples of 1/4 in [lo, hi], and signed zeros.
Gen quarters(int lo, int hi) {
  return [lo, hi](Rng& r) {
    int k = std::uniform_int_distribution<int>(lo * 4, hi * 4)(r);
    if (k == 0) return (r() & 1) ? 0x80000000u : 0u;
    return bits_of(static_cast<float>(k) * 0.25f);
  };
}

// Inputs from one generator per input (all components alike).
std::function<void(Rng&, int64_t, const std::vector<ir::Type>&, std::vector<Words>&)> inputs_from(
    std::vector<Gen> gens) {
  return [gens](Rng& rng, int64_t n, const std::vector<ir::Type>& types, std::vector<Words>& out) {
    out.assign(types.size(), Words{});
    for (size_t j = 0; j < types.size(); ++j) {
      out[j].resize(static_cast<size_t>(n * types[j].width));
      for (auto& w : out[j]) w = gens[j](rng);
    }
  };
}

// Outputs start as a recognizable pattern, so that discarded and unwritten elements show.
void pattern_prefill(int64_t n, const std::vector<ir::Type>& types, std::vector<Words>& out) {
  out.assign(types.size(), Words{});
  for (size_t j = 0; j < types.size(); ++j) {
    out[j].resize(static_cast<size_t>(n * types[j].width));
    for (size_t k = 0; k < out[j].size(); ++k)
      out[j][k] = types[j].is_float() ? bits_of(static_cast<float>(k % 1000) + 0.5f)
                                      : static_cast<uint32_t>(0x10000 + k);
  }
}

Case control(const std::string& name, std::function<Program()> build, std::vector<Gen> gens) {
  Case c;
  c.name = "control." + name;
  c.category = "control";
  c.build = std::move(build);
  c.generate = inputs_from(std::move(gens));
  c.exact_program = true;
  c.prefill = pattern_prefill;
  return c;
}

Case if_case() {
  return control("if",
                 [] {
                   return program("control_if", [] {
                     Input<Float> x("x");
                     Input<Int> k("k");
                     Output<Float> y("y");
                     Output<Int> code("code");
                     RILL_IF(x < -2.0f) {
                       y = -x;
                       code = 1;
                     }
                     RILL_ELSE_IF(x < 0.0f) {
                       y = x * 2.0f;
                       code = 2;
                     }
                     RILL_ELSE_IF(x == 0.0f) {
                       y = 1.0f;
                       code = 3;
                     }
                     RILL_ELSE {
                       RILL_IF(k > 5 && !(k == 8)) {
                         y = x + to_float(k);
                         code = 4;
                       }
                       RILL_ELSE {
                         y = floor(x);
                         code = 5 + k;
                       }
                       RILL_ENDIF;
                     }
                     RILL_ENDIF;
                   });
                 },
                 {quarters(-8, 8), ints(0, 10)});
}

Case while_case() {
  return control("while",
                 [] {
                   return program("control_while", [] {
                     Input<Int> n("n");
                     Output<Int> steps("steps");
                     Output<Int> peak("peak");
                     Int v = max(n, 1);
                     Int s = 0;
                     Int p = v;
                     RILL_WHILE(v != 1 && s < 1000) {
                       RILL_IF((v & 1) == 0) {
                         v = v >> 1;
                       }
                       RILL_ELSE {
                         v = v * 3 + 1;
                       }
                       RILL_ENDIF;
                       p = max(p, v);
                       s += 1;
                     }
                     RILL_ENDWHILE;
                     steps = s;
                     peak = p;
                   });
                 },
                 {ints(-3, 100000)});
}

Case do_until_case() {
  return control("do_until",
                 [] {
                   return program("control_do_until", [] {
                     Input<Int> n("n");
                     Output<Int> digits("digits");
                     Output<Int> sum("sum");
                     Int v = n;
                     Int d = 0;
                     Int s = 0;
                     RILL_DO {
                       s += v % 10;
                       v = v / 10;
                       d += 1;
                     }
                     RILL_UNTIL(v == 0);
                     digits = d;
                     sum = s;
                   });
                 },
                 {[](Rng& r) { return static_cast<uint32_t>(r()); }});
}

Case for_case() {
  return control("for_break_continue",
                 [] {
                   return program("control_for", [] {
                     Input<Int> n("n");
                     Output<Int> acc_out("acc");
                     Output<Int> last_out("last");
                     Int acc = 0;
                     Int last = -1;
                     RILL_FOR(Int i = 0, i < n, i += 1) {
                       RILL_IF(i % 3 == 0) {
                         RILL_CONTINUE;
                       }
                       RILL_ENDIF;
                       RILL_IF(acc > 200) {
                         RILL_BREAK;
                       }
                       RILL_ENDIF;
                       acc += i * 2;
                       last = i;
                     }
                     RILL_ENDFOR;
                     acc_out = acc;
                     last_out = last;
                   });
                 },
                 {ints(-5, 60)});
}

Case nested_case() {
  return control("nested_loops",
                 [] {
                   return program("control_nested", [] {
                     Input<Int> n("n");
                     Output<Int> count("count");
                     Output<Int> pairs("pairs");
                     Output<Int> odd("odd");
                     Int c = 0;
                     Int pr = 0;
                     Int od = 0;
                     RILL_FOR(Int i = 0, i < n, i += 1) {
                       RILL_IF(i == 5) {
                         RILL_CONTINUE;
                       }
                       RILL_ENDIF;
                       Int j = 0;
                       RILL_WHILE(j < i) {
                         RILL_IF(j * i > 40) {
                           RILL_BREAK;
                         }
                         RILL_ENDIF;
                         pr += 1;
                         j += 1;
                       }
                       RILL_ENDWHILE;
                       c += j;
                       // continue inside do-until still evaluates the condition
                       Int m = 0;
                       RILL_DO {
                         m += 1;
                         RILL_IF(m % 2 == 0) {
                           RILL_CONTINUE;
                         }
                         RILL_ENDIF;
                         od += 1;
                       }
                       RILL_UNTIL(m >= 3);
                     }
                     RILL_ENDFOR;
                     count = c;
                     pairs = pr;
                     odd = od;
                   });
                 },
                 {ints(-2, 20)});
}

Case discard_case() {
  return control("discard",
                 [] {
                   return program("control_discard", [] {
                     Input<Int> n("n");
                     Input<Float> x("x");
                     Output<Int> o("o");
                     Output<Float> f("f");
                     RILL_IF(n % 4 == 1) {
                       RILL_DISCARD;
                     }
                     RILL_ENDIF;
                     o = n * 2;
                     // f is written on one path only: elsewhere it keeps the stream's previous
                     // value
                     RILL_IF(x < 0.0f) {
                       f = -x;
                     }
                     RILL_ENDIF;
                     RILL_FOR(Int i = 0, i < 8, i += 1) {
                       RILL_IF(i == n % 7 && n % 5 == 0) {
                         RILL_DISCARD;
                       }
                       RILL_ENDIF;
                     }
                     RILL_ENDFOR;
                   });
                 },
                 {ints(-1000, 1000), quarters(-4, 4)});
}

Case arrays_case() {
  auto table = std::make_shared<Array<Float>>(37, "table");
  auto grid = std::make_shared<Array<Int2>>(5, 4, "grid");
  auto vol = std::make_shared<Array<Float4>>(3, 3, 2, "vol");
  {
    std::vector<float> t(37);
    for (size_t k = 0; k < t.size(); ++k) t[k] = static_cast<float>(k) * 0.25f - 3.0f;
    table->upload(t);
    std::vector<glm::ivec2> g(20);
    for (size_t k = 0; k < g.size(); ++k)
      g[k] = glm::ivec2(static_cast<int>(k), -7 * static_cast<int>(k));
    grid->upload(g);
    std::vector<glm::vec4> v(18);
    for (size_t k = 0; k < v.size(); ++k) {
      float f = static_cast<float>(k);
      v[k] = glm::vec4(f, -f, f * 0.5f, 100.0f + f);
    }
    vol->upload(v);
  }
  Case c = control("arrays",
                   [table, grid, vol] {
                     return program("control_arrays", [&] {
                       Input<Int> i("i");
                       Input<Int> j("j");
                       Input<Int> k("k");
                       Output<Float> t("t");
                       Output<Int2> g("g");
                       Output<Float4> v("v");
                       Output<Float> sum("sum");
                       t = (*table)[i];
                       g = (*grid)(i, j);
                       v = (*vol)(i, j, k);
                       Float s = 0.0f;
                       RILL_FOR(Int q = 0, q < j, q += 1) {
                         s += (*table)[q + i];
                       }
                       RILL_ENDFOR;
                       sum = s;
                     });
                   },
                   {ints(-5, 45), ints(-3, 8), ints(-2, 4)});
  return c;
}

Case uniforms_case() {
  auto gain = std::make_shared<Uniform<Float>>(2.0f, "gain");
  auto off = std::make_shared<Uniform<Int3>>(glm::ivec3(1, 2, 3), "off");
  auto on = std::make_shared<Uniform<Int>>(1, "on");
  Case c = control("uniforms",
                   [gain, off, on] {
                     return program("control_uniforms", [&] {
                       Input<Float> x("x");
                       Input<Int> n("n");
                       Output<Float> y("y");
                       Output<Int3> m("m");
                       y = x * (*gain) + 0.5f;
                       m = (*off) * n + Int3(1, -1, 0);
                       RILL_IF(*on != 0 && n < off->x()) {
                         m.y() = 7;
                       }
                       RILL_ENDIF;
                     });
                   },
                   {quarters(-16, 16), ints(-20, 20)});
  c.launches = 2;
  c.set_launch = [gain, off, on](int launch) {
    gain->set(launch == 0 ? 2.0f : -0.25f);
    off->set(launch == 0 ? glm::ivec3(1, 2, 3) : glm::ivec3(-7, 0, 100));
    on->set(launch == 0 ? 1 : 0);
  };
  return c;
}

Case swizzle_and_mask_case() {
  return control("swizzle_mask",
                 [] {
                   return program("control_swizzle", [] {
                     Input<Float4> a("a");
                     Input<Int4> n("n");
                     Output<Float4> o("o");
                     Output<Int4> p("p");
                     Output<Float2> q("q");
                     Float4 v = a;
                     v(0, 1) = a(3, 2);
                     v.z() = a.x() + 1.0f;
                     o = Float4(v(2, 0, 1), v.w() - a.y());
                     Int4 w = n;
                     w(1, 3) = n(0, 0) * 2;
                     w.x() = n.w();
                     p = w(3, 2, 1, 0);
                     q = a(1, 1) * Float2(a.x(), 2.0f);
                   });
                 },
                 {quarters(-64, 64), ints(-100000, 100000)});
}

Case coords_case() {
  Case c = control("element_coord",
                   [] {
                     return program("control_coords", [] {
                       Input<Int> n("n");
                       Output<Int2> xy("xy");
                       Output<Int> idx("idx");
                       Int2 e = element_coord();
                       xy = e * 2 + Int2(n, 0);
                       idx = element_index() - e.x() - e.y() * 61;
                     });
                   },
                   {ints(-3, 3)});
  c.width = 61;
  c.elements = 61 * 37;
  return c;
}

// Lane-group operations (rill/Group.h) used so that no output depends on the group: the
// reference interpreter runs a group of one, the simd backend its lanes, so every backend
// and mode must give the interpreter's bits. A group-wide early out whose sides agree, a
// loop that runs while any lane of the group still needs it (as a packet traversal does),
// a broadcast from the element's own lane, and invariants of any group (its own ballot bit
// set, min <= own <= max, a count of at least one, the lane inside the group).
Case group_case() {
  Case c = control(
      "group_independent",
      [] {
        return program("control_group", [] {
          Input<Float> x("x");
          Input<Int> k("k");
          Output<Float> y("y");
          Output<Int> code("code");
          Float r = x;
          RILL_IF(group_any(x > 0.0f)) {
            r = select(x > 0.0f, x * 2.0f, x);
          }
          RILL_ENDIF;
          y = group_broadcast(r, lane_index());
          Int i = 0, sum = 0;
          RILL_WHILE(group_any(i < (k & 7))) {
            RILL_IF(i < (k & 7)) {
              sum += i * 3 + 1;
            }
            RILL_ENDIF;
            i += 1;
          }
          RILL_ENDWHILE;
          Int lane = lane_index();
          Int4 b = group_ballot(Bool(true));
          Int word =
              select(lane < 32, b.x(), select(lane < 64, b.y(), select(lane < 96, b.z(), b.w())));
          Bool ok = ((word >> (lane & 31)) & 1) == 1;
          ok = ok && group_min(k) <= k && group_max(k) >= k && group_count(k > -1000000) >= 1;
          ok = ok && lane >= 0 && lane < group_size() && group_all(Bool(true));
          code = select(ok, sum, Int(-1));
        });
      },
      {quarters(-64, 64), ints(-100, 100)});
  c.elements = 1001;  // the simd backend's last group is short
  return c;
}

}  // namespace

std::vector<Case> control_cases() {
  return {if_case(),     while_case(),    do_until_case(),
          for_case(),    nested_case(),   discard_case(),
          arrays_case(), uniforms_case(), swizzle_and_mask_case(),
          coords_case(), group_case()};
}

}  // namespace rill::conformance
