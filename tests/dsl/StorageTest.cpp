// The host and device copies of a stream's data (dsl/src/Stream.cpp, detail::Storage): which
// words of the device copy are stale after the host writes some of them, so that a backend
// uploads only those (Array::upload(first, data)).
#include <gtest/gtest.h>

#include <rill/rill.h>

namespace rill::detail {
namespace {

struct FakeBuffer : DeviceBuffer {};

// A backend that is never called: the tests keep the host copy current.
Backend* const kBackend = reinterpret_cast<Backend*>(0x10);

using Words = std::pair<size_t, size_t>;

TEST(Storage, RangeWritesMakeOnlyTheirWordsStale) {
  Storage s;
  s.init(ir::float_type(3), 100);  // 300 words
  EXPECT_EQ(s.stale_words(), Words(0, 300));
  s.set_device_buffer(kBackend, std::make_unique<FakeBuffer>());
  EXPECT_EQ(s.stale_words(), Words(0, 300));  // a new buffer holds nothing yet
  s.mark_device_current(kBackend);
  EXPECT_TRUE(s.is_device_current(kBackend));
  const uint64_t version = s.version();
  s.host_data_for_write_range(30, 6)[31] = 7u;
  EXPECT_FALSE(s.is_device_current(kBackend));
  EXPECT_GT(s.version(), version);
  EXPECT_EQ(s.stale_words(), Words(30, 36));
  s.host_data_for_write_range(270, 3);  // a second range: both, and what lies between
  EXPECT_EQ(s.stale_words(), Words(30, 273));
  s.mark_device_current(kBackend);
  EXPECT_EQ(s.stale_words(), Words(0, 0));
  s.host_data_for_write();  // any other write: all of it
  EXPECT_EQ(s.stale_words(), Words(0, 300));
  s.host_data_for_write_range(3, 3);  // stale already: stays whole
  EXPECT_EQ(s.stale_words(), Words(0, 300));
  EXPECT_EQ(s.host_data_for_read()[31], 7u);
}

}  // namespace
}  // namespace rill::detail
