#pragma once
// The imucal LCM messages (generated at build time from lcmtypes/*.lcm by lcm-gen) and the LCM C++ API.
// Include this header rather than the generated ones: lcm-gen's decode() reads the 8-byte fingerprint
// through a loop GCC 12 cannot see through, and once decode() is inlined into our code -Wmaybe-uninitialized
// fires on it even though the headers are SYSTEM includes (GCC reports middle-end warnings at the inlined
// call site). The pragma covers only the generated code's source lines, not the includer's.
#include <lcm/lcm-cpp.hpp>

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include "imucal/calibration_t.hpp"      // IWYU pragma: export
#include "imucal/calibration_trigger_t.hpp"  // IWYU pragma: export
#include "imucal/daemon_status_t.hpp"    // IWYU pragma: export
#include "imucal/heading_sample_t.hpp"   // IWYU pragma: export
#include "imucal/imu_batch_t.hpp"        // IWYU pragma: export
#include "imucal/imu_sample_t.hpp"       // IWYU pragma: export
#include "imucal/mag_field_t.hpp"        // IWYU pragma: export
#include "imucal/session_progress_t.hpp" // IWYU pragma: export
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
