#include "hubrt/assembly/hub_assembly.h"

#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "hubrt/assembly/diagnostics_stage.h"
#include "hubrt/assembly/hub_types.h"
#include "hubrt/assembly/linux_device_libraries.h"
#include "hubrt/blackbox/ring_size.h"
#include "hubrt/hal/board/board_loader.h"
#include "hubrt/hal/board/board_requirements.h"
#include "hubrt/hal/linux/backend.h"
#include "hubrt/hub_api/black_box_streams.h"
#include "hubrt/hub_api/hub_type.h"
#include "hubrt/hub_api/subscriptions.h"
#include "hubrt/hub_api/topic_names.h"

#include "diagnostic_msgs_reflect.h"

namespace hubrt::assembly {
namespace {

std::string known_hub_types() {
  std::vector<std::string_view> names;
  for (const hub_api::HubType* type : hub_types()) names.push_back(type->name());
  return fmt::format("{}", fmt::join(names, ", "));
}

Expected<void> apply_overrides(const AssemblyRequest& request, config::HubConfig& config) {
  if (request.name) {
    if (!config::is_ros_name_token(*request.name)) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("hub name '{}' cannot be used in a topic name: use letters, digits and "
                                    "underscores, starting with a letter",
                                    *request.name));
    }
    config.name = *request.name;
  }
  if (request.rate_hz) {
    const double rate = *request.rate_hz;
    if (!(rate > 0.0 && rate <= 1000.0)) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("rate {} Hz is out of range (0, 1000]", rate));
    }
    config.rate_hz = rate;
    config.period = std::chrono::nanoseconds(static_cast<std::int64_t>(std::llround(1e9 / rate)));
    if (config.command_timeout < 2 * config.period) config.command_timeout = 2 * config.period;
  }
  return {};
}

}  // namespace

Expected<CheckedHub> check_hub(const AssemblyRequest& request) {
  CheckedHub out;
  if (request.loaded_board != nullptr) {
    out.board = *request.loaded_board;
  } else {
    auto board = hal::load_board(request.board_file);
    if (!board) return std::move(board).error();
    out.board = std::move(*board);
  }
  if (request.loaded_hub != nullptr) {
    out.config = *request.loaded_hub;
  } else {
    auto config = config::load_hub_config(request.hub_file);
    if (!config) return std::move(config).error();
    out.config = std::move(*config);
  }
  if (auto ok = apply_overrides(request, out.config); !ok) return std::move(ok).error();

  const hub_api::HubType* type = find_hub_type(out.config.type);
  if (type == nullptr) {
    return make_error(ErrorCode::kNotFound, fmt::format("{}: unknown hub type '{}' (this hubd knows: {})",
                                                        out.config.file, out.config.type, known_hub_types()));
  }
  auto required = type->requirements(out.config);
  if (!required) return std::move(required).error();
  if (auto ok = hal::check_requirements(out.board, *required); !ok) return std::move(ok).error();
  if (request.backend == BackendKind::kLinux) {
    if (auto ok = check_device_libraries(*required, linux_device_libraries()); !ok)
      return std::move(ok).error();
  }
  if (auto ok = type->check(out.config); !ok) return std::move(ok).error();
  if (request.backend == BackendKind::kFake && request.simulation == nullptr) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: the fake backend is not available: {}",
                                                               out.board.file, kNoSimulationHint));
  }
  if (request.backend == BackendKind::kFake && !out.board.simulation) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: board {} has no simulation section: the fake backend cannot run it",
                                  out.board.file, out.board.name));
  }
  return out;
}

Expected<std::unique_ptr<AssembledHub>> assemble_hub(const AssemblyRequest& request, const Clock& clock) {
  auto log = request.log ? request.log : spdlog::default_logger();
  auto out = std::make_unique<AssembledHub>();

  auto checked = check_hub(request);
  if (!checked) return std::move(checked).error();
  out->board = std::move(checked->board);
  out->config = std::move(checked->config);
  const hub_api::HubType* type = find_hub_type(out->config.type);

  // The start stamp decides which of two twins is the later one (twin_rules.h).
  const std::int64_t started_ns = clock.now().wall.ns_since_epoch;
  auto participant =
      dds::Participant::create(request.domain, out->config.name,
                               hub_user_data(started_ns, out->config.ros_namespace, out->config.name));
  if (!participant) return std::move(participant).error();
  out->participant.emplace(std::move(*participant));
  if (request.black_box_directory && out->config.blackbox.enabled) {
    const config::HubBlackBox& settings = out->config.blackbox;
    blackbox::BlackBoxOptions box;
    box.hub_name = out->config.name;
    box.span = settings.span;
    // Unless the hub file says, a span of what this hub records at its own rates (a fixed 8 MiB,
    // touched at start, was most of a board hub's memory).
    box.memory_bytes = settings.memory_bytes.value_or(blackbox::ring_bytes_for(
        settings.span, blackbox::hub_recorded_rates(out->config.nodes.size(), out->config.rate_hz,
                                                    out->config.diagnostics_hz)));
    box.directory = settings.directory.empty() ? *request.black_box_directory : settings.directory;
    box.directory_bytes = settings.directory_bytes;
    auto made = blackbox::BlackBox::create(std::move(box));
    if (!made) return std::move(made).error();
    out->black_box = std::move(*made);
  }
  std::unique_ptr<TwinWatch> watch;
  if (request.twin_check) {
    auto started = TwinWatch::start(*out->participant, out->config.ros_namespace, out->config.name, log);
    if (!started) return std::move(started).error();
    watch = std::move(*started);
  }

  // While the twin check's window runs (it counts from TwinWatch::start): what needs no verdict —
  // no device, no State writer (a running twin would see one as a twin of its own), nothing
  // published. The hub object, the readers of other hubs' States, the /diagnostics endpoint and
  // the sim bridge's entities.
  runtime::HubOptions options;
  options.type = out->config.type;
  options.name = out->config.name;
  options.period = out->config.period;
  options.log = log;
  out->hub = std::make_unique<runtime::Hub>(std::move(options));
  out->subscriptions = std::make_unique<hub_api::Subscriptions>(out->config, *out->participant);
  std::optional<DiagnosticsStage::Endpoint> diagnostics_endpoint;
  if (out->config.diagnostics_hz > 0) {
    auto endpoint = DiagnosticsStage::open_endpoint(*out->participant);
    if (!endpoint) return std::move(endpoint).error();
    endpoint->writer.set_sample_hook(hub_api::black_box_stream(
        out->black_box.get(), std::string(hub_api::kDiagnosticsTopic),
        msgs::type_info_of<diagnostic_msgs_msg_dds__DiagnosticArray_>(), dds::Qos::ros2_default(), false));
    diagnostics_endpoint.emplace(std::move(*endpoint));
  }
  std::unique_ptr<Simulation::PreparedBridge> prepared_bridge;
  if (request.backend == BackendKind::kFake) {
    auto prepared =
        request.simulation->prepare_bridge(*out->participant, out->config.name, out->config.ros_namespace);
    if (!prepared) return std::move(prepared).error();
    prepared_bridge = std::move(*prepared);
  }

  // Before the backend: a twin refused here has opened no device and touched no output.
  if (watch && *request.twin_check > Duration::zero()) {
    if (auto alone = watch->check_at_start(*request.twin_check, request.twin_quiet); !alone)
      return std::move(alone).error();
  }
  out->twin_watch = std::move(watch);

  if (request.backend == BackendKind::kFake) {
    auto simulated = request.simulation->open_backend(out->board, clock);
    if (!simulated) {
      return make_error(simulated.error().code,
                        fmt::format("fake backend for {}: {}", out->board.file, simulated.error().message));
    }
    out->simulated = std::move(*simulated);
    out->devices = &out->simulated->backend();
  } else {
    out->backend = std::make_unique<hal::LinuxBackend>(linux_device_libraries());
    out->devices = out->backend.get();
  }

  out->hub->begin_opening_devices();
  const hub_api::HubContext context{out->config,         out->board, *out->devices, *out->participant,
                                    request.waker,       log,        clock,         *out->subscriptions,
                                    out->black_box.get()};
  if (auto built = type->build(context, *out->hub); !built) return std::move(built).error();
  // Other hubs' States are taken before the nodes step, so the logic sees this cycle's.
  if (auto stage = out->subscriptions->make_stage()) out->hub->add_first_stage(std::move(stage));

  if (diagnostics_endpoint) {
    const auto interval =
        std::chrono::nanoseconds(static_cast<std::int64_t>(1e9 / out->config.diagnostics_hz));
    out->hub->add_stage(DiagnosticsStage::create(
        std::move(*diagnostics_endpoint), *out->hub, out->board.name, interval, out->config.command_timeout,
        out->config.immediate_state_interval, request.log_lines_dropped));
  }
  if (out->twin_watch) {
    auto twins =
        std::make_unique<TwinStage>(*out->twin_watch, out->hub->alerts(),
                                    HubStamp{started_ns, out->participant->guid()}, request.request_stop);
    out->twins = twins.get();
    out->hub->add_stage(std::move(twins));
  }
  if (out->simulated) {
    out->hub->add_stage(
        request.simulation->bridge(std::move(prepared_bridge), out->board, *out->simulated, log));
  }
  if (out->black_box) {
    out->black_box->seal();
    auto service = BlackBoxService::start(*out->participant, *out->black_box, out->config.ros_namespace,
                                          out->config.name, log);
    if (!service) return std::move(service).error();
    out->black_box_service = std::move(*service);
    out->hub->add_stage(out->black_box_service->make_stage(*out->hub));
  }
  return out;
}

}  // namespace hubrt::assembly
