// The DigitalInput / DigitalOutput contract: what every backend's GPIO lines must do, as a
// parameterised gtest suite written against the interfaces only. A backend provides a harness
// (a Backend, a chip, free lines, and a way to drive an input's electrical level and to see an
// output's) and instantiates:
//
//   INSTANTIATE_TEST_SUITE_P(MyBackend, DigitalIoContract, ::testing::Values(DigitalIoContractBackend{
//       "MyBackend", [] { return std::make_unique<MyHarness>(); }}), DigitalIoContractName{});
//
// A factory may return nullptr when the backend cannot run here (the tests skip, saying why).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/hal/backend.h"

namespace hubrt::hal::contract {

class DigitalIoHarness {
 public:
  virtual ~DigitalIoHarness() = default;

  virtual Backend& backend() = 0;
  // What configs put in `chip` to reach the chip under test (path, name or label).
  [[nodiscard]] virtual std::string chip() const = 0;
  [[nodiscard]] virtual unsigned num_lines() const = 0;
  // Free lines of that chip the suite may request: at least 2 for inputs, 2 for outputs, distinct,
  // and not driven from outside before the suite drives them.
  [[nodiscard]] virtual std::vector<unsigned> input_lines() const = 0;
  [[nodiscard]] virtual std::vector<unsigned> output_lines() const = 0;
  // Drives an input line from outside to an electrical level, as a sensor would.
  virtual Expected<void> drive(unsigned line, bool high) = 0;
  // The electrical level an output line is driven to.
  virtual Expected<bool> observe(unsigned line) = 0;
  // The time the suite passes to read(); advance() moves it (debouncing is tested through it).
  [[nodiscard]] virtual Time now() const = 0;
  virtual void advance(Duration d) = 0;
  // True when an edge driven by drive() is visible to the next read() at once. The kernel
  // delivers edge events through an interrupt thread, a moment later: then the suite polls.
  [[nodiscard]] virtual bool edges_immediate() const { return true; }
  // Makes the chip disappear (unplugged, driver gone). False when the backend cannot: skipped.
  virtual bool remove_chip() { return false; }
};

struct DigitalIoContractBackend {
  std::string name;
  std::function<std::unique_ptr<DigitalIoHarness>()> make;
  std::string skip_reason = "this backend cannot run here";  // when make() returns nullptr
};

struct DigitalIoContractName {
  std::string operator()(const ::testing::TestParamInfo<DigitalIoContractBackend>& backend) const {
    return backend.param.name;
  }
};

class DigitalIoContract : public ::testing::TestWithParam<DigitalIoContractBackend> {
 protected:
  void SetUp() override;

  [[nodiscard]] DigitalInputConfig input_config(std::size_t index,
                                                Polarity polarity = Polarity::kActiveHigh) const;
  [[nodiscard]] DigitalOutputConfig output_config(std::size_t index,
                                                  Polarity polarity = Polarity::kActiveHigh,
                                                  bool initial = false, bool safe = false) const;
  // Open or fail the test.
  std::unique_ptr<DigitalInput> open(const DigitalInputConfig& config);
  std::unique_ptr<DigitalOutput> open(const DigitalOutputConfig& config);
  void drive(unsigned line, bool high);
  bool observe(unsigned line);
  bool read(DigitalInput& input);

  std::unique_ptr<DigitalIoHarness> harness_;
};

}  // namespace hubrt::hal::contract
