// Rill: write stream kernels once, in C++, and run them on every backend.
//
// This umbrella header is all a user needs:
//   values (Value.h), operators and math (Operators.h, Math.h), control flow
//   (ControlFlow.h), kernel interfaces (Parameters.h), streams and arrays (Stream.h),
//   records (Record.h), reductions (Reduce.h), programs (Program.h), connecting and combining them (Algebra.h), and
//   compiling and launching kernels (Kernel.h), lane-group operations (Group.h).
#pragma once

#include "rill/Algebra.h"
#include "rill/Backend.h"
#include "rill/CompileProgressLine.h"
#include "rill/ControlFlow.h"
#include "rill/Group.h"
#include "rill/Kernel.h"
#include "rill/Math.h"
#include "rill/Operators.h"
#include "rill/Parameters.h"
#include "rill/Print.h"
#include "rill/Program.h"
#include "rill/Record.h"
#include "rill/Random.h"
#include "rill/Reduce.h"
#include "rill/Stream.h"
#include "rill/Value.h"
