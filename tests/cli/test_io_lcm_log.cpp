// The LCM log reader against logs written by LCM's own writer (lcm::LogFile): every event comes back equal,
// in order. Lengths that LCM's C reader trusted (a data length of INT_MAX made it crash) are refused before
// anything is allocated; garbage between events is skipped and counted; a last event cut short ends the log.
#include <gtest/gtest.h>

#include <climits>
#include <fstream>

#include "imucal/io/errors.hpp"
#include "imucal/io/lcm_log_file.hpp"
#include "imucal/lcmtypes.hpp"
#include "scratch_dir.hpp"

namespace imucal::io {
namespace {

using imucal::testing::ScratchDir;

std::string writeWithLcm(const ScratchDir& dir, int events) {
  const std::string path = dir / "log.lcm";
  lcm::LogFile log(path, "w");
  for (int i = 0; i < events; ++i) {
    lcm::LogEvent e{};
    e.timestamp = 1'700'000'000'000'000 + i * 10'000;
    e.channel = i % 2 ? "IMUCAL_HEADING" : "IMUCAL_IMU";
    std::vector<std::uint8_t> data(static_cast<std::size_t>(i * 7 % 50), static_cast<std::uint8_t>(i));
    e.datalen = static_cast<int32_t>(data.size());
    e.data = data.data();
    log.writeEvent(&e);
  }
  return path;
}

// An event header as lcm-logger writes it, with lengths of the test's choosing.
std::string header(std::int64_t number, std::int64_t timestamp, std::int32_t channel_len, std::int32_t data_len) {
  std::string h;
  const auto put = [&](std::uint64_t v, int bytes) {
    for (int i = bytes - 1; i >= 0; --i) h += static_cast<char>((v >> (8 * i)) & 0xFF);
  };
  put(0xEDA1DA01u, 4);
  put(static_cast<std::uint64_t>(number), 8);
  put(static_cast<std::uint64_t>(timestamp), 8);
  put(static_cast<std::uint32_t>(channel_len), 4);
  put(static_cast<std::uint32_t>(data_len), 4);
  return h;
}

TEST(IoLcmLog, ReadsWhatLcmWroteEventForEvent) {
  ScratchDir dir;
  LcmLogReader reader(writeWithLcm(dir, 40));
  for (int i = 0; i < 40; ++i) {
    const auto e = reader.next();
    ASSERT_TRUE(e.has_value()) << i;
    EXPECT_EQ(e->number, i);
    EXPECT_EQ(e->timestamp, 1'700'000'000'000'000 + i * 10'000);
    EXPECT_EQ(e->channel, i % 2 ? "IMUCAL_HEADING" : "IMUCAL_IMU");
    EXPECT_EQ(e->data, std::vector<std::uint8_t>(static_cast<std::size_t>(i * 7 % 50), static_cast<std::uint8_t>(i)));
  }
  EXPECT_FALSE(reader.next().has_value());
  EXPECT_EQ(reader.skippedBytes(), 0u);
  EXPECT_FALSE(reader.truncated());
}

TEST(IoLcmLog, ForgedLengthsAreSkippedNotAllocated) {
  ScratchDir dir;
  const std::string good = header(7, 5, 3, 2) + "ABC" + "xy";
  // Each forged header is followed by bytes that hold no sync word, then one good event.
  for (const auto& [channel_len, data_len] : std::vector<std::pair<std::int32_t, std::int32_t>>{
           {3, INT_MAX}, {3, -1}, {3, INT_MIN}, {0, 2}, {-5, 2}, {2000, 2}, {3, LcmLogReader::kMaxDataBytes + 1}}) {
    const std::string path = dir.write("forged.lcm", header(1, 1, channel_len, data_len) + std::string(40, 'z') + good);
    LcmLogReader reader(path);
    const auto e = reader.next();
    ASSERT_TRUE(e.has_value()) << channel_len << " " << data_len;
    EXPECT_EQ(e->number, 7);
    EXPECT_EQ(e->channel, "ABC");
    EXPECT_EQ(std::string(e->data.begin(), e->data.end()), "xy");
    // The forged header's 24 bytes after its sync word, its sync word, and the 40 filler bytes.
    EXPECT_EQ(reader.skippedBytes(), 4u + 24u + 40u) << channel_len << " " << data_len;
    EXPECT_FALSE(reader.next().has_value());
  }
}

TEST(IoLcmLog, LengthsBeyondTheFileEndItAsTruncated) {
  ScratchDir dir;
  const std::string path = dir.write("cut.lcm", header(0, 1, 3, 2) + "ABCxy" + header(1, 2, 3, 1000) + "ABC" + "only a few");
  LcmLogReader reader(path);
  ASSERT_TRUE(reader.next().has_value());
  EXPECT_FALSE(reader.next().has_value());
  EXPECT_TRUE(reader.truncated());
  LcmLogReader empty(dir.write("empty.lcm", ""));
  EXPECT_FALSE(empty.next().has_value());
  EXPECT_FALSE(empty.truncated());
}

TEST(IoLcmLog, MissingFileOrDirectoryIsAnInputError) {
  ScratchDir dir;
  const std::string missing = dir / "none.lcm", directory = dir.path().string();
  EXPECT_THROW(LcmLogReader{missing}, InputError);
  EXPECT_THROW(LcmLogReader{directory}, InputError);
}

}  // namespace
}  // namespace imucal::io
