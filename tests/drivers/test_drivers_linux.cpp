// The Linux pieces where this machine can run them: clear errors for a missing I2C bus, GPIO chip or CAN
// interface (this kernel has none of them; the VM test covers the working paths), the event loop with
// timers and signals, and the emulated data-ready line.
#include <gtest/gtest.h>
#include <signal.h>

#include <cerrno>
#include <chrono>

#include "imucal/drivers/data_ready_line.hpp"
#include "imucal/drivers/can_socket.hpp"
#include "imucal/app/event_loop.hpp"
#include "imucal/drivers/gpiod_data_ready_line.hpp"
#include "imucal/drivers/icm42688_config_file.hpp"
#include "imucal/drivers/linux_i2c_bus.hpp"
#include "imucal/io/errors.hpp"

namespace imucal::drivers {
namespace {

TEST(DriversLinux, MissingI2cBusNamesThePathAndErrno) {
  try {
    LinuxI2cBus bus("/dev/i2c-97");
    FAIL() << "opened a bus that does not exist";
  } catch (const I2cError& e) {
    EXPECT_EQ(e.errorNumber(), ENOENT);
    EXPECT_EQ(std::string(e.what()).rfind("/dev/i2c-97: cannot open the I2C bus: No such file or directory", 0), 0u) << e.what();
  }
}

TEST(DriversLinux, MissingGpioChipIsAClearError) {
  // Goes through libgpiod 1.6's gpiod_chip_open_by_name (the v1 API this file is written against).
  try {
    openGpiodDataReadyLine({"gpiochip97", 5}, "imucal-test");
    FAIL() << "opened a GPIO chip that does not exist";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("GPIO gpiochip97:5: cannot open the chip", 0), 0u) << e.what();
  }
}

TEST(DriversLinux, MissingCanInterfaceIsAClearError) {
  try {
    openSocketCan("vcan97", {});
    FAIL() << "opened a CAN interface that does not exist";
  } catch (const std::runtime_error& e) {
    // Without CAN in the kernel the socket itself fails; with it, the interface lookup.
    EXPECT_EQ(std::string(e.what()).rfind("CAN vcan97: ", 0), 0u) << e.what();
  }
}

TEST(DriversLinux, EventLoopRunsTimersAndFdsAndStopsOnSigterm) {
  app::EventLoop loop;
  loop.stopOnSignals();
  EmulatedDataReadyLine line;
  std::vector<std::int64_t> edges;
  loop.addFd(line.fd(), [&] {
    while (const auto e = line.readEdge()) edges.push_back(*e);
  });
  int ticks = 0;
  loop.addTimer(0.005, [&] {
    if (++ticks <= 3) line.pushEdge(1000 * ticks);
    if (ticks == 5) ::kill(::getpid(), SIGTERM);  // taken by the signalfd, not the default handler
  });
  loop.run();
  EXPECT_EQ(loop.stopSignal(), SIGTERM);
  EXPECT_EQ(ticks, 5);
  EXPECT_EQ(edges, (std::vector<std::int64_t>{1000, 2000, 3000}));
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
}

TEST(DriversLinux, TickTimerGivesTheLatestTickAndTheMissedOnes) {
  const std::int64_t now = std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
  const std::int64_t first = now - 55'000;  // 10 ms ticks that started 55 ms ago: ticks 0..5 have passed
  app::TickTimer timer(first, 10'000);
  std::int64_t missed = -1;
  const auto t = timer.take(&missed);
  ASSERT_TRUE(t);
  EXPECT_EQ((*t - first) % 10'000, 0);
  EXPECT_GE(*t - first, 50'000);
  EXPECT_EQ(missed, (*t - first) / 10'000);
  EXPECT_FALSE(timer.take()) << "nothing pending right after taking";
}

TEST(DriversLinux, Icm42688ConfigErrorsNameFileLineAndKey) {
  const Icm42688FileConfig c = parseIcm42688Config(
      "bus: /dev/i2c-1\naddress: 0x69\naccel_range_g: 8\ngyro_range_dps: 500\nodr_hz: 200\ndata_ready: {chip: gpiochip2, line: 17}\n",
      "imu.yaml");
  EXPECT_EQ(c.bus, "/dev/i2c-1");
  EXPECT_EQ(c.chip.address, 0x69);
  EXPECT_EQ(c.chip.accel_range_g, 8.0);
  EXPECT_EQ(c.poll_hz, 400.0);
  ASSERT_TRUE(c.data_ready);
  EXPECT_EQ(c.data_ready->chip, "gpiochip2");
  EXPECT_EQ(c.data_ready->line, 17);
  EXPECT_EQ(c.process.sensor_id, "icm42688@/dev/i2c-1:0x69");
  const auto message = [](const std::string& yaml) {
    try {
      parseIcm42688Config(yaml, "imu.yaml");
    } catch (const io::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("address: 0x68\n"), "imu.yaml:1: bus: is required");
  EXPECT_NE(message("bus: /dev/i2c-1\naddress: 0x6A\n").find("imu.yaml:2: "), std::string::npos);
  EXPECT_NE(message("bus: /dev/i2c-1\naddress: 0x6A\n").find("0x68..0x69"), std::string::npos);
  EXPECT_NE(message("bus: /dev/i2c-1\naddress: 0x68\ngyro_range_dps: 300\n").find("imu.yaml:3: "), std::string::npos);
  EXPECT_NE(message("bus: /dev/i2c-1\naddress: 0x68\nodr_hz: 300\n").find("not one of the ICM-42688-P's"), std::string::npos);
  EXPECT_NE(message("bus: /dev/i2c-1\naddress: zz\n").find("expected a number such as 0x68"), std::string::npos);
  EXPECT_NE(message("bus: /dev/i2c-1\naddress: 0x68\ndata_ready: {chip: gpiochip0}\n").find("data_ready.line"), std::string::npos);
  EXPECT_NE(message("bus: /dev/i2c-1\naddress: 0x68\naxis_map: [\"+x\", \"+x\", \"-z\"]\n").find("axis_map"), std::string::npos);
}

}  // namespace
}  // namespace imucal::drivers
