// The test executables' main: GoogleTest's own, plus one exit status for CTest's batches.
//
// CTest runs the backend suite and the DSL tests in batches, one process per test suite and
// backend (cmake/RillTestBatches.cmake). A batch whose every case skipped (a backend that
// cannot run on this machine skips its cases, with the reason) exits 77, which the batch's
// SKIP_RETURN_CODE makes CTest report as skipped, not passed. A batch in which some cases ran
// and others skipped passes; GoogleTest lists the skipped ones in its output and
// scripts/test-times counts them in its summary, so a skip is never silent.
#include <gtest/gtest.h>

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  const int status = RUN_ALL_TESTS();
  const testing::UnitTest& unit = *testing::UnitTest::GetInstance();
  const bool all_skipped = unit.skipped_test_count() > 0 && unit.successful_test_count() == 0 &&
                           unit.failed_test_count() == 0;
  return status == 0 && all_skipped ? 77 : status;
}
