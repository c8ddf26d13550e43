#pragma once
// The CSV sample readers' shared harness: the input is written as the file, and what a reader returns is
// held to the promises every reader makes (csv_reader.hpp): samples, with finite, strictly increasing times.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "fuzz_expect.hpp"
#include "fuzz_scratch.hpp"
#include "imucal/io/errors.hpp"

namespace imucal::fuzz {

template <class Sample>
void expectIncreasingTimes(const std::vector<Sample>& samples) {
  expect(!samples.empty(), "a file without samples is an InputError");
  for (std::size_t k = 0; k < samples.size(); ++k) {
    expect(std::isfinite(samples[k].t), "sample time is finite");
    if (k > 0) expect(samples[k].t > samples[k - 1].t, "sample times strictly increase");
  }
}

// The checked samples, or nothing when the reader refused the file with an InputError (its only error).
template <class Reader, class Format>
auto readSamples(Reader read, const std::string& file_name, const Format& format, const std::uint8_t* data,
                 std::size_t size) -> std::optional<decltype(read(std::string(), format))> {
  const std::string path = ScratchDir::instance().write(file_name, data, size);
  try {
    auto samples = read(path, format);
    expectIncreasingTimes(samples);
    return samples;
  } catch (const io::InputError&) {
    return std::nullopt;
  }
}

}  // namespace imucal::fuzz
