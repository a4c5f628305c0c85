// The wiring tables of the deploy guide (docs/deploy.md), generated from the board files so that
// the guide never disagrees with what hubd opens.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/hal/board/board_config.h"

namespace hubrt::packaging {

// The physical pin of the Raspberry Pi 40-pin header that carries `line` of the chip labelled
// `chip_label`: the SoC's GPIO chip of a Pi 1–4 (pinctrl-bcm2835, pinctrl-bcm2711) or a Pi 5
// (pinctrl-rp1), whose line numbers are the BCM numbers. nullopt for other chips and for lines
// that are not on the header. Thread-safe.
std::optional<int> rpi_header_pin(std::string_view chip_label, unsigned line);

// One board's tables as Markdown: a heading, its GPIO lines sorted by chip and line (direction,
// header pin, polarity, bias, debounce, initial and safe levels), its CAN interfaces and its
// Modbus devices. Thread-safe.
std::string wiring_tables(const hal::BoardConfig& board);

// The generated part of the deploy guide: the tables of every board that is not a simulation
// board, sorted by board name. Thread-safe.
std::string wiring_section(std::vector<hal::BoardConfig> boards);

// The markers around the generated part in docs/deploy.md.
inline constexpr std::string_view kBeginMarker =
    "<!-- BEGIN wiring tables: generated from boards/ by `make deploy-docs`; do not edit -->";
inline constexpr std::string_view kEndMarker = "<!-- END wiring tables -->";

// `document` with the text between the markers (each on a line of its own) replaced by
// `generated`. Errors: kInvalidArgument when a marker is missing, given twice or out of order.
// Thread-safe.
Expected<std::string> replace_generated_section(std::string_view document, std::string_view generated);

}  // namespace hubrt::packaging
