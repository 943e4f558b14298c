// Data-dependent control flow: macros that record per-element branches and loops.
//
//   RILL_IF(x < 0.0f) {            RILL_WHILE(i < n) {           RILL_DO {
//     y = -x;                        i += 1;                       z = z * z + c;
//   } RILL_ELSE_IF(x < 1.0f) {     } RILL_ENDWHILE;              } RILL_UNTIL(dot(z, z) > 4.0f);
//     y = x;
//   } RILL_ELSE {                  RILL_FOR(Int i = 0, i < 8, i += 1) {
//     y = 1.0f;                      acc += to_float(i);
//   } RILL_ENDIF;                  } RILL_ENDFOR;
//
// Plus RILL_BREAK, RILL_CONTINUE (innermost loop) and RILL_DISCARD (the element writes
// nothing and is not counted). The braces are optional; each macro opens or closes a C++
// scope itself, so a macro left open fails to compile, and closing one construct with
// another's macro (RILL_ENDWHILE after RILL_IF) throws rill::Error naming both places.
//
// Host `if` and `for` still work inside kernels: they run once, at definition time, and
// decide what code is generated (metaprogramming). Use the macros when the decision depends
// on per-element data.
#pragma once

#include "rill/Value.h"

namespace rill::detail {
inline ir::Operand condition(const Value<bool, 1>& c) { return c.operand(); }
inline ir::Operand condition(bool c) { return ir::Operand::of_const(ir::Constant::of_bool(c)); }
}  // namespace rill::detail

#define RILL_IF(cond) ::rill::detail::begin_if(::rill::detail::condition(cond), RILL_HERE); {
#define RILL_ELSE_IF(cond)                                                                   \
  }                                                                                          \
  ::rill::detail::begin_else_if(RILL_HERE);                                                  \
  ::rill::detail::begin_if(::rill::detail::condition(cond), RILL_HERE);                      \
  {
#define RILL_ELSE } ::rill::detail::begin_else(RILL_HERE); {
#define RILL_ENDIF } ::rill::detail::end_if(RILL_HERE)

#define RILL_WHILE(cond)                                                                      \
  ::rill::detail::begin_while(RILL_HERE);                                                     \
  ::rill::detail::while_body(::rill::detail::condition(cond), RILL_HERE);                     \
  {
#define RILL_ENDWHILE } ::rill::detail::end_while(RILL_HERE)

#define RILL_DO ::rill::detail::begin_do(RILL_HERE); {
#define RILL_UNTIL(cond) \
  }                      \
  ::rill::detail::begin_until(RILL_HERE); \
  ::rill::detail::end_until(::rill::detail::condition(cond), RILL_HERE)

// RILL_FOR(init, cond, step): init runs once before the loop (and may declare the counter,
// scoped to the loop); cond is tested before each iteration; step runs after each one
// (also after RILL_CONTINUE).
#define RILL_FOR(init, cond, step)                                        \
  {                                                                       \
    init;                                                                 \
    ::rill::detail::begin_for(RILL_HERE);                                 \
    ::rill::detail::for_cond(::rill::detail::condition(cond), RILL_HERE); \
    step;                                                                 \
    ::rill::detail::for_body(RILL_HERE);                                  \
    {
#define RILL_ENDFOR                   \
  }                                   \
  ::rill::detail::end_for(RILL_HERE); \
  }

#define RILL_BREAK ::rill::detail::emit_break(RILL_HERE)
#define RILL_CONTINUE ::rill::detail::emit_continue(RILL_HERE)
#define RILL_DISCARD ::rill::detail::emit_discard(RILL_HERE)
