// The one instantiation of fmt's formatting engine that the files including
// hubrt/fmt/vformat_once.h use (that header says why).
#include "hubrt/fmt/vformat_once.h"

#include <fmt/format.h>

#ifdef HUBRT_FMT_VFORMAT_ONCE
FMT_BEGIN_NAMESPACE
namespace detail {
template void vformat_to<char>(buffer<char>& buf, basic_string_view<char> spec,
                               basic_format_args<FMT_BUFFER_CONTEXT(char)> args, locale_ref loc);
}  // namespace detail
FMT_END_NAMESPACE
#endif
