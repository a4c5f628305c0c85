// The ROS 1 ECU approach side by side with hubd in one run (issue 14 point 4): a roscpp Dock ECU
// (hubrt_bench_ros1_ecu: 10 Hz state loop, immediate echo from its command callback) measured by a
// roscpp planner over ROS 1, the same ECU measured over DDS through hubbridge (the bridge's added
// latency), and hubd's Dock ECU (10 Hz) measured over DDS. Per target: command -> echo latency,
// start -> first State (not through the bridge), period jitter, CPU and RSS of the ECU process.
//   hubrt_bench_ros1 --out FILE [--samples N] [--seconds S] [--runs R]
#include <fstream>
#include <mutex>
#include <thread>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <netinet/in.h>
#include <ros/ros.h>
#include <ros/serialization.h>
#include <sys/socket.h>
#include <topic_tools/shape_shifter.h>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/writer.h"
#include "hubrt/msgs/sample_memory.h"
#include "hubrt/ros1/codec.h"
#include "hubrt/ros1/definition.h"

#include "bench_common.h"
#include "dock_reflect.h"
#include "dock_typed.h"
#include "proc_stats.h"
#include "raw_dds.h"

namespace hubrt::bench {
namespace {

using CommandWire = hub_msgs_msg_dds__DockCommand_;
using StateWire = hub_msgs_msg_dds__DockState_;

struct Arrival {
  double t = 0;
  std::string action;
};

class Client {
 public:
  virtual ~Client() = default;
  virtual void send(const std::string& action) = 0;
  virtual std::vector<Arrival> take() = 0;
};

// A planner over DDS (hubd, or the ROS 1 ECU through hubbridge).
class DdsClient : public Client {
 public:
  static std::unique_ptr<DdsClient> create() {
    auto client = std::unique_ptr<DdsClient>(new DdsClient());
    auto config = dds::domain_config_from_environment();
    client->participant_.emplace(std::move(*dds::Participant::create(*config, "bench_planner")));
    client->command_topic_.emplace(
        std::move(*dds::Topic<CommandWire>::create(*client->participant_, "/dock/command")));
    client->state_topic_.emplace(
        std::move(*dds::Topic<StateWire>::create(*client->participant_, "/dock_ecu/dock/state")));
    client->writer_.emplace(
        std::move(*dds::Writer<CommandWire>::create(*client->participant_, *client->command_topic_)));
    client->reader_.emplace(
        std::move(*dds::Reader<StateWire>::create(*client->participant_, *client->state_topic_)));
    return client;
  }
  void send(const std::string& action) override {
    hub_msgs::DockCommand command;
    command.set_target_type("dock");
    command.set_target_name("dock");
    command.set_action(action);
    (void)writer_->write(command.wire());
  }
  std::vector<Arrival> take() override {
    std::vector<Arrival> out;
    while (true) {
      auto taken = reader_->take_next(sample_);
      if (!taken.is_ok() || !taken.value()) break;
      out.push_back({mono_now(), sample_.get().echo.action});
    }
    return out;
  }

 private:
  DdsClient() = default;
  std::optional<dds::Participant> participant_;
  std::optional<dds::Topic<CommandWire>> command_topic_;
  std::optional<dds::Topic<StateWire>> state_topic_;
  std::optional<dds::Writer<CommandWire>> writer_;
  std::optional<dds::Reader<StateWire>> reader_;
  dds::Sample<StateWire> sample_;
};

// A planner over ROS 1 (roscpp, ShapeShifter with the ROS 1 form of ros2/hub_msgs).
class Ros1Client : public Client {
 public:
  Ros1Client(ros::NodeHandle& node, const ros1::Messages& messages)
      : command_md5_(*ros1::md5sum(messages, "hub_msgs/DockCommand")),
        command_definition_(*ros1::full_definition(messages, "hub_msgs/DockCommand")) {
    topic_tools::ShapeShifter shape;
    shape.morph(command_md5_, "hub_msgs/DockCommand", command_definition_, "false");
    publisher_ = shape.advertise(node, "/dock/command", 10);
    ros::SubscribeOptions options;
    options.initByFullCallbackType<const ros::MessageEvent<topic_tools::ShapeShifter const>&>(
        "/dock_ecu/dock/state", 100,
        [this](const ros::MessageEvent<topic_tools::ShapeShifter const>& e) { on_state(e); });
    options.md5sum = *ros1::md5sum(messages, "hub_msgs/DockState");
    options.datatype = "hub_msgs/DockState";
    options.transport_hints = ros::TransportHints().tcpNoDelay();
    subscriber_ = node.subscribe(options);
  }
  ~Ros1Client() override { msgs::free_contents(msgs::type_info_of<StateWire>(), &state_); }
  void send(const std::string& action) override {
    hub_msgs::DockCommand command;
    command.set_target_type("dock");
    command.set_target_name("dock");
    command.set_action(action);
    std::vector<std::uint8_t> bytes;
    ros1::encode(msgs::type_info_of<CommandWire>(), &command.wire(), bytes);
    topic_tools::ShapeShifter shape;
    shape.morph(command_md5_, "hub_msgs/DockCommand", command_definition_, "false");
    ros::serialization::IStream stream(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
    shape.read(stream);
    publisher_.publish(shape);
  }
  std::vector<Arrival> take() override {
    const std::lock_guard lock(mutex_);
    return std::exchange(arrivals_, {});
  }
  [[nodiscard]] std::uint32_t publishers() const { return subscriber_.getNumPublishers(); }

 private:
  void on_state(const ros::MessageEvent<topic_tools::ShapeShifter const>& event) {
    const double t = mono_now();
    const auto& message = *event.getConstMessage();
    std::vector<std::uint8_t> bytes(message.size());
    ros::serialization::OStream stream(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
    message.write(stream);
    if (ros1::decode(msgs::type_info_of<StateWire>(), bytes, &state_)) return;
    const std::lock_guard lock(mutex_);
    arrivals_.push_back({t, state_.echo.action});
  }

  std::string command_md5_;
  std::string command_definition_;
  ros::Publisher publisher_;
  ros::Subscriber subscriber_;
  StateWire state_{};
  std::mutex mutex_;
  std::vector<Arrival> arrivals_;
};

void sleep_s(double s) {
  std::this_thread::sleep_for(std::chrono::duration<double>(s));
}

// Waits up to `timeout_s` for a State; returns the arrival time or -1.
double first_arrival(Client& client, double timeout_s) {
  const double end = mono_now() + timeout_s;
  while (mono_now() < end) {
    auto got = client.take();
    if (!got.empty()) return got.front().t;
    sleep_s(0.0002);
  }
  return -1;
}

nlohmann::ordered_json latency(Client& client, int samples) {
  std::vector<double> ms;
  int lost = 0;
  for (int i = 0; i < samples; ++i) {
    const std::string action = i % 2 == 0 ? "reset" : "monitor";
    client.take();
    const double t0 = mono_now();
    client.send(action);
    bool echoed = false;
    while (!echoed && mono_now() - t0 < 1.0) {
      for (const Arrival& a : client.take()) {
        if (!echoed && a.action == action) {
          ms.push_back((a.t - t0) * 1e3);
          echoed = true;
        }
      }
      if (!echoed) sleep_s(0.0001);
    }
    lost += echoed ? 0 : 1;
    sleep_s(0.03);  // past hubd's immediate-State budget (10 ms); well within the 1 s timeout
  }
  auto out = summary_json(ms);
  out["lost"] = lost;
  return out;
}

nlohmann::ordered_json heartbeat(Client& client, pid_t pid, double seconds) {
  client.take();
  std::vector<double> arrivals;
  const auto before = read_proc(pid);
  const double t0 = mono_now();
  while (mono_now() - t0 < seconds) {
    for (const Arrival& a : client.take()) arrivals.push_back(a.t);
    sleep_s(0.0002);
  }
  const auto after = read_proc(pid);
  std::vector<double> jitter_ms;
  for (std::size_t i = 1; i < arrivals.size(); ++i)
    jitter_ms.push_back(std::abs(arrivals[i] - arrivals[i - 1] - 0.1) * 1e3);
  nlohmann::ordered_json out;
  out["states"] = arrivals.size();
  out["jitter_ms"] = summary_json(jitter_ms);
  if (before && after) {
    out["cpu_pct"] = cpu_percent(*before, *after, mono_now() - t0);
    out["rss_mb"] = after->rss_mb;
  }
  return out;
}

int free_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof addr;
  ::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr);
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  ::close(fd);
  return ntohs(addr.sin_port);
}

}  // namespace
}  // namespace hubrt::bench

int main(int argc, char** argv) {
  using namespace hubrt::bench;  // NOLINT(google-build-using-namespace): the program's own namespace
  std::string out_path;
  int samples = 200;
  double seconds = 10;
  int runs = 5;
  CLI::App app("ROS 1 ECU (roscpp, directly and through hubbridge) side by side with hubd");
  app.add_option("--out", out_path, "JSON results")->required();
  app.add_option("--samples", samples, "Commands per latency measurement");
  app.add_option("--seconds", seconds, "Heartbeat window");
  app.add_option("--runs", runs, "Start -> first State runs per target");
  CLI11_PARSE(app, argc, argv);
  auto domain = join_private_domain();
  if (!domain) {
    fmt::print(stderr, "{}\n", domain.error().message);
    return 2;
  }
  const std::string bin =
      std::filesystem::path(hubd_path()).parent_path().parent_path().parent_path().string();  // build dir
  const std::string ecu_path = bin + "/bench/hubrt_bench_ros1_ecu";
  const std::string bridge_path = bin + "/firmware/hubbridge/hubbridge";
  const std::string master_uri = fmt::format("http://127.0.0.1:{}", free_port());
  ::setenv("ROS_MASTER_URI", master_uri.c_str(), 1);
  hubrt::test_support::Environment env = {{"ROS_MASTER_URI", master_uri}};
  auto master = hubrt::test_support::ChildProcess::start(
      "/usr/bin/rosmaster", {"--core", "-p", master_uri.substr(master_uri.rfind(':') + 1)}, env);
  if (!master) return 2;
  sleep_s(2.0);
  auto messages = hubrt::ros1::load_ros2_tree_as_ros1(source_dir() + "/ros2");
  ros::init(argc, argv, "bench_planner", ros::init_options::NoRosout | ros::init_options::NoSigintHandler);
  ros::NodeHandle node;
  ros::AsyncSpinner spinner(1);
  spinner.start();
  Ros1Client ros1_client(node, *messages);
  auto dds_client = DdsClient::create();
  nlohmann::ordered_json result;

  // hubd's Dock ECU at 10 Hz, over DDS.
  progress("hubd: start -> first State");
  std::vector<double> hubd_start;
  for (int i = 0; i < runs; ++i) {
    dds_client->take();
    const double t0 = mono_now();
    auto hubd = start_hubd({"--hub", "dock_ecu"});
    const double first = first_arrival(*dds_client, 15);
    if (first > 0) hubd_start.push_back((first - t0) * 1e3);
    stop(*hubd);
    sleep_s(0.5);
  }
  result["hubd"]["first_state_ms"] = summary_json(hubd_start);
  auto hubd = start_hubd({"--hub", "dock_ecu"});
  first_arrival(*dds_client, 15);
  progress("hubd: heartbeat, CPU, RSS");
  result["hubd"]["heartbeat"] = heartbeat(*dds_client, hubd->pid(), seconds);
  progress("hubd: command -> echo");
  result["hubd"]["echo_ms"] = latency(*dds_client, samples);
  stop(*hubd);

  // The roscpp ECU over ROS 1.
  progress("roscpp ECU: start -> first State");
  std::vector<double> ecu_start;
  for (int i = 0; i < runs; ++i) {
    ros1_client.take();
    const double t0 = mono_now();
    auto ecu = hubrt::test_support::ChildProcess::start(ecu_path, {}, env);
    if (!ecu) {
      fmt::print(stderr, "{}\n", ecu.error().message);
      return 2;
    }
    const double first = first_arrival(ros1_client, 15);
    if (first > 0) ecu_start.push_back((first - t0) * 1e3);
    stop(*ecu);
    sleep_s(0.5);
  }
  result["ros1_ecu"]["first_state_ms"] = summary_json(ecu_start);
  auto ecu = hubrt::test_support::ChildProcess::start(ecu_path, {}, env);
  first_arrival(ros1_client, 15);
  sleep_s(1.0);  // the ECU's subscriber connects to our command publisher
  progress("roscpp ECU: heartbeat, CPU, RSS");
  result["ros1_ecu"]["heartbeat"] = heartbeat(ros1_client, ecu->pid(), seconds);
  progress("roscpp ECU: command -> echo over ROS 1");
  result["ros1_ecu"]["echo_ms"] = latency(ros1_client, samples);

  // The same ECU through hubbridge, from DDS.
  const std::string file =
      std::filesystem::temp_directory_path() / fmt::format("hubrt-bench-bridge-{}.yaml", getpid());
  std::ofstream(file) << "name: dock_ecu\nmsg_dir: " << source_dir() << "/ros2\nbridges:\n"
                      << "  - {ros1_topic: /dock_ecu/dock/state, dds_topic: /dock_ecu/dock/state, type: "
                         "hub_msgs/DockState, direction: ros1_to_dds}\n"
                      << "  - {ros1_topic: /dock/command, dds_topic: /dock/command, type: "
                         "hub_msgs/DockCommand, direction: dds_to_ros1}\n";
  auto bridge = hubrt::test_support::ChildProcess::start(bridge_path, {file}, env);
  first_arrival(*dds_client, 15);
  sleep_s(2.0);  // the ECU's subscriber connects to the bridge's command publisher
  progress("roscpp ECU through hubbridge: heartbeat, command -> echo over DDS");
  result["ros1_ecu_bridged"]["heartbeat"] = heartbeat(*dds_client, bridge->pid(), seconds);
  result["ros1_ecu_bridged"]["echo_ms"] = latency(*dds_client, samples);
  stop(*bridge);
  stop(*ecu);
  std::filesystem::remove(file);
  spinner.stop();
  ros::shutdown();
  stop(*master);
  auto written = write_json(out_path, result);
  if (!written) {
    fmt::print(stderr, "{}\n", written.error().message);
    return 1;
  }
  return 0;
}
