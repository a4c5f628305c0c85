// fmt's formatting engine, compiled once instead of in every file that formats.
//
// fmt 9 (Debian bookworm's) defines its engine, detail::vformat_to<char>, as a template in
// fmt/format.h, and every fmt::format_to, fmt::format_to_n and spdlog call instantiates it there:
// the engine and every writer it calls (integers, floats, padding), about 800 functions. At -O0
// with ASan+UBSan that was a third of a test object's compile (clang -ftime-trace of
// command_age_test.cc: 1.26 s of 2.19 s of its functions' optimisation was fmt's). Declared an
// explicit instantiation here, the files use the one compiled in libhubrt_fmt_vformat
// (src/vformat_once.cc). fmt 10 made the engine an ordinary function of its library, which is
// what this does for 9; with any other fmt the header declares nothing.
#pragma once

#include <fmt/core.h>

#if FMT_VERSION >= 90000 && FMT_VERSION < 100000
#define HUBRT_FMT_VFORMAT_ONCE 1
FMT_BEGIN_NAMESPACE
namespace detail {
extern template void vformat_to<char>(buffer<char>& buf, basic_string_view<char> spec,
                                      basic_format_args<FMT_BUFFER_CONTEXT(char)> args, locale_ref loc);
}  // namespace detail
FMT_END_NAMESPACE
#endif
