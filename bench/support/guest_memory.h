// The memory of a program run under qemu-user, apart from qemu's own.
//
// Why: the board programs are measured for arm64 and armhf on this x86 machine under qemu-user
// (issue 16, point 3: "qemu figure with the reason"). There the process is qemu: its RSS holds qemu
// itself (its executable, its translation buffer, its heap: about 21 MB beside hubd on 2026-11-28)
// and the guest program's own mappings (its executable, its libraries from the sysroot, its heap,
// its threads' stacks). qemu-user maps the guest into its own address space below qemu's own
// mappings (a 64-bit guest at 0x5500000000 with Debian 12's qemu 7.2; qemu's static executable
// and its brk heap sit far above), so the guest's share is every mapping below the lowest of qemu's
// executable and qemu's heap.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include <sys/types.h>

namespace hubrt::bench {

// Resident memory, and how much of it is anonymous: pages no file backs (heap, stacks, the written
// copies of a library's data), which only swap could take back, unlike the pages of a program's
// code and read-only data, which the kernel drops under pressure and reads again from the file.
// In the unit its function names (kB or MB).
struct Resident {
  double rss = 0;
  double anon = 0;
};

// The Rss and Anonymous (kB) of the guest's mappings in a /proc/<pid>/smaps text of an emulator
// whose executable is `emulator_path`; nullopt when neither the executable nor [heap] is among the
// mappings.
std::optional<Resident> guest_rss_kb(std::string_view smaps, const std::string& emulator_path);

// For a running process: its guest memory in MB when its executable is qemu-user ("qemu-*"),
// nullopt otherwise (a native process, or /proc unreadable).
std::optional<Resident> emulated_guest_rss_mb(pid_t pid);

}  // namespace hubrt::bench
