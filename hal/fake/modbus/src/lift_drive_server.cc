#include "hubrt/hal/fake/lift_drive_server.h"

#include <poll.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <string>
#include <system_error>
#include <thread>

#include <arpa/inet.h>
#include <modbus/modbus.h>
#include <sys/eventfd.h>
#include <sys/socket.h>

namespace hubrt::hal::fake {
namespace {

namespace ld = protocol::lift_drive;

constexpr int kMaxClients = 8;
constexpr int kListenBacklog = 4;
// modbus_reply sleeps for the context's response timeout before answering some malformed
// requests; keep that stall short in the server thread.
constexpr std::uint32_t kServerFlushPauseUs = 10'000;

struct ModbusFree {
  void operator()(modbus_t* ctx) const noexcept { modbus_free(ctx); }
};
struct MappingFree {
  void operator()(modbus_mapping_t* mapping) const noexcept { modbus_mapping_free(mapping); }
};
using ContextPtr = std::unique_ptr<modbus_t, ModbusFree>;
using MappingPtr = std::unique_ptr<modbus_mapping_t, MappingFree>;

std::uint16_t be16(const std::uint8_t* bytes, int at) noexcept {
  return static_cast<std::uint16_t>(MODBUS_GET_INT16_FROM_INT8(bytes, at));
}

void close_fd(int& fd) noexcept {
  if (fd >= 0) ::close(fd);
  fd = -1;
}

}  // namespace

// One listening period: the libmodbus context, the sockets and the serving thread.
class LiftDriveServer::Session {
 public:
  Session(LiftDriveServer& owner, ContextPtr ctx, MappingPtr mapping, int listen_fd, int wake_fd)
      : owner_(owner),
        ctx_(std::move(ctx)),
        mapping_(std::move(mapping)),
        listen_fd_(listen_fd),
        wake_fd_(wake_fd) {
    clients_.fill(-1);
    thread_ = std::thread([this] { serve(); });
  }

  ~Session() {
    const std::uint64_t one = 1;
    if (::write(wake_fd_, &one, sizeof one) < 0) {
      // The eventfd cannot be full with one write per session; nothing better to do than join.
    }
    thread_.join();
    for (int& fd : clients_) close_fd(fd);
    close_fd(listen_fd_);
    close_fd(wake_fd_);
  }

  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

 private:
  void serve() noexcept {
    for (;;) {
      std::array<pollfd, 2 + kMaxClients> fds{};
      nfds_t n = 0;
      fds[n++] = pollfd{wake_fd_, POLLIN, 0};
      fds[n++] = pollfd{listen_fd_, POLLIN, 0};
      for (const int fd : clients_) {
        if (fd >= 0) fds[n++] = pollfd{fd, POLLIN, 0};
      }
      if (::poll(fds.data(), n, -1) < 0) {
        if (errno == EINTR) continue;
        return;
      }
      if (fds[0].revents != 0) return;
      if ((fds[1].revents & POLLIN) != 0) accept_client();
      for (nfds_t i = 2; i < n; ++i) {
        if (fds[i].revents == 0) continue;
        if (!serve_one_request(fds[i].fd)) drop_client(fds[i].fd);
      }
    }
  }

  void accept_client() noexcept {
    const int fd = modbus_tcp_accept(ctx_.get(), &listen_fd_);
    if (fd < 0) return;
    for (int& slot : clients_) {
      if (slot < 0) {
        slot = fd;
        owner_.accepted_.fetch_add(1);
        return;
      }
    }
    ::close(fd);  // as many connections as a small drive accepts
  }

  void drop_client(int fd) noexcept {
    for (int& slot : clients_) {
      if (slot == fd) close_fd(slot);
    }
  }

  // False when the connection is finished (closed by the peer, or garbage on it).
  bool serve_one_request(int fd) noexcept {
    modbus_set_socket(ctx_.get(), fd);
    std::array<std::uint8_t, MODBUS_TCP_MAX_ADU_LENGTH> query{};
    const int length = modbus_receive(ctx_.get(), query.data());
    if (length < 0) return false;
    if (length == 0) return true;
    return answer(query.data(), length);
  }

  bool answer(const std::uint8_t* query, int length) noexcept {
    const int hl = modbus_get_header_length(ctx_.get());
    const std::uint8_t unit = query[hl - 1];
    const std::uint8_t function = query[hl];
    if (unit != owner_.drive_.config().unit_id || !owner_.answering_.load()) {
      owner_.unanswered_.fetch_add(1);
      return true;
    }
    const Time now = owner_.clock_.now().mono;
    const std::uint16_t address = be16(query, hl + 1);
    ModbusException exception = ModbusException::kNone;
    switch (function) {
      case MODBUS_FC_READ_COILS:
      case MODBUS_FC_READ_DISCRETE_INPUTS:
      case MODBUS_FC_READ_HOLDING_REGISTERS:
      case MODBUS_FC_READ_INPUT_REGISTERS:
        break;
      case MODBUS_FC_WRITE_SINGLE_COIL: {
        const std::uint16_t value = be16(query, hl + 3);
        if (value != 0xFF00 && value != 0x0000) {
          exception = ModbusException::kIllegalDataValue;
          break;
        }
        const bool on = value == 0xFF00;
        exception = owner_.drive_.write_coils(address, std::span<const bool>(&on, 1), now);
        break;
      }
      case MODBUS_FC_WRITE_SINGLE_REGISTER: {
        const std::uint16_t value = be16(query, hl + 3);
        exception = owner_.drive_.write_holding(address, std::span<const std::uint16_t>(&value, 1), now);
        break;
      }
      case MODBUS_FC_WRITE_MULTIPLE_COILS:
        exception = write_coils(query, length, hl, address, now);
        break;
      case MODBUS_FC_WRITE_MULTIPLE_REGISTERS:
        exception = write_registers(query, length, hl, address, now);
        break;
      default:
        exception = ModbusException::kIllegalFunction;
        break;
    }
    if (!wait_answer_delay()) return false;
    // Counted before sending, so that a client holding the answer always sees the count.
    owner_.answered_.fetch_add(1);
    int sent = 0;
    if (exception != ModbusException::kNone) {
      sent = modbus_reply_exception(ctx_.get(), query, static_cast<unsigned int>(exception));
    } else {
      fill_mapping(owner_.drive_.read(now));
      sent = modbus_reply(ctx_.get(), query, length, mapping_.get());
    }
    return sent >= 0;
  }

  // False when the server is stopping meanwhile.
  bool wait_answer_delay() noexcept {
    const Duration delay(owner_.answer_delay_ns_.load());
    if (delay <= Duration::zero()) return true;
    pollfd stop{wake_fd_, POLLIN, 0};
    const auto ms = std::chrono::ceil<std::chrono::milliseconds>(delay).count();
    return ::poll(&stop, 1, static_cast<int>(ms)) == 0;
  }

  ModbusException write_coils(const std::uint8_t* query, int length, int hl, std::uint16_t address,
                              Time now) noexcept {
    const int count = be16(query, hl + 3);
    const int bytes = query[hl + 5];
    if (count < 1 || count > MODBUS_MAX_WRITE_BITS || bytes != (count + 7) / 8 || length < hl + 6 + bytes) {
      return ModbusException::kIllegalDataValue;
    }
    std::array<std::uint8_t, MODBUS_MAX_WRITE_BITS> bits{};
    modbus_set_bits_from_bytes(bits.data(), 0, static_cast<unsigned int>(count), query + hl + 6);
    std::array<bool, MODBUS_MAX_WRITE_BITS> values{};
    for (int i = 0; i < count; ++i) values[i] = bits[i] != 0;
    return owner_.drive_.write_coils(address, std::span<const bool>(values.data(), count), now);
  }

  ModbusException write_registers(const std::uint8_t* query, int length, int hl, std::uint16_t address,
                                  Time now) noexcept {
    const int count = be16(query, hl + 3);
    const int bytes = query[hl + 5];
    if (count < 1 || count > MODBUS_MAX_WRITE_REGISTERS || bytes != 2 * count || length < hl + 6 + bytes) {
      return ModbusException::kIllegalDataValue;
    }
    std::array<std::uint16_t, MODBUS_MAX_WRITE_REGISTERS> values{};
    for (int i = 0; i < count; ++i) values[i] = be16(query, hl + 6 + 2 * i);
    return owner_.drive_.write_holding(address, std::span<const std::uint16_t>(values.data(), count), now);
  }

  // modbus_reply answers reads from (and applies writes to) the mapping: load it with the
  // drive's registers as of this request.
  void fill_mapping(const LiftDriveRegisters& r) noexcept {
    for (int i = 0; i < ld::control::kCoilCount; ++i) {
      mapping_->tab_bits[i] = static_cast<std::uint8_t>((r.control_word() >> i) & 1U);
    }
    for (int i = 0; i < ld::status::kDiscreteInputCount; ++i) {
      mapping_->tab_input_bits[i] = static_cast<std::uint8_t>((r.status_word() >> i) & 1U);
    }
    for (int i = 0; i < ld::holding::kCount; ++i) mapping_->tab_registers[i] = r.holding[i];
    for (int i = 0; i < ld::input::kCount; ++i) mapping_->tab_input_registers[i] = r.input[i];
  }

  LiftDriveServer& owner_;
  ContextPtr ctx_;
  MappingPtr mapping_;
  int listen_fd_;
  int wake_fd_;
  std::array<int, kMaxClients> clients_{};
  std::thread thread_;
};

Expected<std::unique_ptr<LiftDriveServer>> LiftDriveServer::start(LiftDrive& drive, const Clock& clock,
                                                                  LiftDriveServerOptions options) {
  std::unique_ptr<LiftDriveServer> server(new LiftDriveServer(drive, clock, std::move(options)));
  const std::lock_guard lock(server->lifecycle_mutex_);
  if (Expected<void> up = server->listen_and_serve(); !up) return std::move(up).error();
  return server;
}

LiftDriveServer::LiftDriveServer(LiftDrive& drive, const Clock& clock, LiftDriveServerOptions options)
    : drive_(drive), clock_(clock), options_(std::move(options)), port_(options_.port) {}

LiftDriveServer::~LiftDriveServer() {
  go_down();
}

void LiftDriveServer::go_down() noexcept {
  const std::lock_guard lock(lifecycle_mutex_);
  session_.reset();
}

Expected<void> LiftDriveServer::come_back() {
  const std::lock_guard lock(lifecycle_mutex_);
  if (session_) return {};
  return listen_and_serve();
}

bool LiftDriveServer::is_up() const noexcept {
  const std::lock_guard lock(lifecycle_mutex_);
  return session_ != nullptr;
}

Expected<void> LiftDriveServer::listen_and_serve() {
  const std::string where = "lift drive simulator on " + options_.address + ":" + std::to_string(port_);
  in_addr parsed{};
  if (::inet_pton(AF_INET, options_.address.c_str(), &parsed) != 1) {
    return make_error(ErrorCode::kInvalidArgument, where + ": not an IPv4 address");
  }
  ContextPtr ctx(modbus_new_tcp(options_.address.c_str(), port_));
  if (!ctx) return make_error(ErrorCode::kIo, where + ": modbus_new_tcp failed: " + modbus_strerror(errno));
  modbus_set_response_timeout(ctx.get(), 0, kServerFlushPauseUs);
  int listen_fd = modbus_tcp_listen(ctx.get(), kListenBacklog);
  if (listen_fd < 0) {
    const int err = errno;
    return make_error(err == EADDRINUSE ? ErrorCode::kBusy : ErrorCode::kIo,
                      where + ": cannot listen: " + std::generic_category().message(err));
  }
  sockaddr_in bound{};
  socklen_t bound_len = sizeof bound;
  if (::getsockname(listen_fd, reinterpret_cast<sockaddr*>(&bound), &bound_len) != 0) {
    const int err = errno;
    close_fd(listen_fd);
    return make_error(ErrorCode::kIo,
                      where + ": getsockname failed: " + std::generic_category().message(err));
  }
  port_ = ntohs(bound.sin_port);
  int wake_fd = ::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  MappingPtr mapping(modbus_mapping_new(ld::control::kCoilCount, ld::status::kDiscreteInputCount,
                                        ld::holding::kCount, ld::input::kCount));
  if (wake_fd < 0 || !mapping) {
    close_fd(listen_fd);
    close_fd(wake_fd);
    return make_error(ErrorCode::kIo, where + ": cannot allocate the server's resources");
  }
  session_ = std::make_unique<Session>(*this, std::move(ctx), std::move(mapping), listen_fd, wake_fd);
  return {};
}

}  // namespace hubrt::hal::fake
