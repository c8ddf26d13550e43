// imucal: field calibration of consumer MEMS IMUs (simulate, calibrate, Monte Carlo study, bound, plan, diagnose;
// watch, echo and log2csv for the daemon's LCM messages).
#include <cstdio>
#include <exception>
#include <iostream>

#include "commands.hpp"
#include "imucal/app/command_line.hpp"
#include "imucal/io/errors.hpp"

int main(int argc, char** argv) {
  CLI::App app{"imucal: calibrate a MEMS IMU by hand with an error-state Kalman filter"};
  imucal::app::CommandLine command_line(app, "imucal");
  app.require_subcommand(1);
  imucal::cli::addSimulateCommand(app);
  imucal::cli::addCalibrateCommand(app);
  imucal::cli::addMonteCarloCommand(app);
  imucal::cli::addBoundCommand(app);
  imucal::cli::addPlanCommand(app);
  imucal::cli::addDiagnoseCommand(app);
  imucal::cli::addWatchCommand(app);
  imucal::cli::addEchoCommand(app);
  imucal::cli::addLog2CsvCommand(app);
  imucal::cli::addMagcalCommand(app);
  imucal::cli::addValidateCommand(app);
  imucal::cli::addNoiseCommand(app);
  try {
    if (const auto status = command_line.parse(argc, argv)) return *status;
  } catch (const imucal::io::InputError& e) {
    std::cerr << "imucal: input error: " << e.what() << '\n';
    return 2;
  } catch (const imucal::cli::ResultRefused& e) {
    std::cerr << "imucal: refused: " << e.what() << '\n';
    return imucal::cli::kExitRefused;
  } catch (const imucal::io::OutputError& e) {
    std::cerr << "imucal: output error: " << e.what() << '\n';
    return 3;
  } catch (const std::exception& e) {
    std::cerr << "imucal: error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
