// What rill-trace is doing, for the message when memory runs out ("rill-trace: out of memory
// while building the grid of 12000 triangles"): each step sets it before it starts.
#pragma once

#include <string>

namespace trace_cli {

// Per thread: a sequence's frames are written on a thread of their own.
inline thread_local std::string g_doing = "starting";

}  // namespace trace_cli
