#include "realtime.h"

#include <pthread.h>
#include <sched.h>

#include <cerrno>
#include <cstring>

#include <fmt/format.h>
#include <sys/mman.h>
#include <sys/resource.h>

#include "hubrt/base/sanitizers.h"

namespace hubrt::hubd {
namespace {

std::string limit_text(int resource) {
  rlimit limit{};
  if (getrlimit(resource, &limit) != 0) return "unknown";
  return limit.rlim_cur == RLIM_INFINITY ? std::string("unlimited") : std::to_string(limit.rlim_cur);
}

}  // namespace

Expected<void> enter_realtime(int priority) {
  if (priority < sched_get_priority_min(SCHED_FIFO) || priority > sched_get_priority_max(SCHED_FIFO)) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("realtime priority {} is outside SCHED_FIFO's {}..{}", priority,
                                  sched_get_priority_min(SCHED_FIFO), sched_get_priority_max(SCHED_FIFO)));
  }
  const int old_policy = sched_getscheduler(0);
  sched_param old_param{};
  sched_getparam(0, &old_param);
  sched_param param{};
  param.sched_priority = priority;
  // sched(7): an unprivileged thread may set a real-time policy only up to RLIMIT_RTPRIO;
  // CAP_SYS_NICE lifts that limit. Anything else is EPERM.
  if (sched_setscheduler(0, SCHED_FIFO, &param) != 0) {
    const int error = errno;
    return make_error(ErrorCode::kPermissionDenied,
                      fmt::format("--realtime: cannot run under SCHED_FIFO at priority {}: {} (needs "
                                  "CAP_SYS_NICE or an RLIMIT_RTPRIO of at least {}, which is {} here; "
                                  "the unit sets LimitRTPRIO=)",
                                  priority, std::strerror(error), priority, limit_text(RLIMIT_RTPRIO)));
  }
#if defined(HUBRT_SANITIZE_ADDRESS) || defined(HUBRT_SANITIZE_THREAD)
  // The sanitizers map terabytes of shadow memory: locking it all would exhaust the machine.
  sched_setscheduler(0, old_policy, &old_param);
  return make_error(ErrorCode::kFailedPrecondition,
                    "--realtime: a sanitizer build (ASan/TSan) cannot lock its memory (its shadow "
                    "memory is terabytes); use a release build");
#endif
  // Locked memory is resident memory: every thread started from here on (Cyclone's, a Modbus
  // worker) would lock its whole stack, 8 MiB each with glibc's default (RLIMIT_STACK), about
  // 65 MB for a hub's threads. pthread_setattr_default_np(3) sets the size new threads get when
  // their creator asks for none, as Cyclone's ddsrt_thread_create does unless configured.
  pthread_attr_t attr;
  if (pthread_attr_init(&attr) == 0) {
    if (pthread_attr_setstacksize(&attr, kRealtimeThreadStackBytes) == 0) pthread_setattr_default_np(&attr);
    pthread_attr_destroy(&attr);
  }
  // mlockall(2): MCL_FUTURE also locks what is mapped later (stacks of threads started after
  // this, heap growth); without CAP_IPC_LOCK everything locked must fit RLIMIT_MEMLOCK.
  if (mlockall(MCL_CURRENT | MCL_FUTURE) != 0) {
    const int error = errno;
    sched_setscheduler(0, old_policy, &old_param);
    return make_error(ErrorCode::kPermissionDenied,
                      fmt::format("--realtime: cannot lock the process's memory (mlockall): {} (needs "
                                  "CAP_IPC_LOCK or an RLIMIT_MEMLOCK large enough for the whole "
                                  "process, which is {} bytes here; the unit sets LimitMEMLOCK=infinity)",
                                  std::strerror(error), limit_text(RLIMIT_MEMLOCK)));
  }
  return {};
}

}  // namespace hubrt::hubd
