// The test executables' main: GoogleTest's own, plus one exit status for CTest's batches.
//
// CTest runs the backend suite and the DSL tests in batches, one process per test suite and
// backend (cmake/RillTestBatches.cmake). A batch whose every case skipped (a backend that
// cannot run on this machine skips its cases, with the reason) exits 77, which the batch's
// SKIP_RETURN_CODE makes CTest report as skipped, not passed. A batch in which some cases ran
// and others skipped passes; GoogleTest lists the skipped ones in its output and
// scripts/test-times counts them in its summary, so a skip is never silent.
//
// Tests run the vulkan backend with the Khronos validation layer on (RILL_VULKAN_VALIDATION,
// docs/backends.md#vulkan) unless the environment says otherwise: a message from the layer
// becomes the launch's or compile's Error, which fails the test.
#include <gtest/gtest.h>

#include <cstdlib>

int main(int argc, char** argv) {
  setenv("RILL_VULKAN_VALIDATION", "on", 0);
  testing::InitGoogleTest(&argc, argv);
  const int status = RUN_ALL_TESTS();
  const testing::UnitTest& unit = *testing::UnitTest::GetInstance();
  const bool all_skipped = unit.skipped_test_count() > 0 && unit.successful_test_count() == 0 &&
                           unit.failed_test_count() == 0;
  return status == 0 && all_skipped ? 77 : status;
}
