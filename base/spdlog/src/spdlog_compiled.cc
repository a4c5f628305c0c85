// spdlog compiled into hubrt's static builds (../CMakeLists.txt says why): the definitions spdlog
// keeps in its *-inl.h headers, which a program built with SPDLOG_COMPILED_LIB does not include,
// and the explicit instantiations of the templates those programs use but do not define. What is
// instantiated here is what hubrt's programs use: a sink of their own on base_sink (hubd's
// stderr sink, tests' sinks) with either mutex, and the colour console sink that spdlog's registry
// makes as the default logger before a program sets its own.
#ifndef SPDLOG_COMPILED_LIB
#error "spdlog_compiled.cc is only built with SPDLOG_COMPILED_LIB (base/spdlog/CMakeLists.txt)"
#endif

#include <mutex>

#include <spdlog/common-inl.h>
#include <spdlog/details/backtracer-inl.h>
#include <spdlog/details/log_msg-inl.h>
#include <spdlog/details/log_msg_buffer-inl.h>
#include <spdlog/details/null_mutex.h>
#include <spdlog/details/os-inl.h>
#include <spdlog/details/periodic_worker-inl.h>
#include <spdlog/details/registry-inl.h>
#include <spdlog/logger-inl.h>
#include <spdlog/pattern_formatter-inl.h>
#include <spdlog/sinks/ansicolor_sink-inl.h>
#include <spdlog/sinks/base_sink-inl.h>
#include <spdlog/sinks/sink-inl.h>
#include <spdlog/sinks/stdout_color_sinks-inl.h>
#include <spdlog/spdlog-inl.h>

template class spdlog::sinks::base_sink<std::mutex>;
template class spdlog::sinks::base_sink<spdlog::details::null_mutex>;
template class spdlog::sinks::ansicolor_sink<spdlog::details::console_mutex>;
template class spdlog::sinks::ansicolor_stdout_sink<spdlog::details::console_mutex>;
template class spdlog::sinks::ansicolor_stderr_sink<spdlog::details::console_mutex>;
