#!/usr/bin/python3
"""A Dock ECU written the way the paper's ROS 1 ECUs were: a rospy node that publishes its State
from a rate loop and takes its Command in a subscriber callback. It keeps the wire contract of
hubs/dock_ecu (README.md, "The wire contract"; firmware/runtime command_tracker.h) as far as a
rate loop can:

  - a valid command whose content differs from the echo, or the first after none was in force,
    takes effect: t_plus restarts; identical repeats only feed the watchdog;
  - no valid command for longer than the timeout: fresh_msg false, "command timeout" in
    error_list, lifecycle SAFE; the old command is never re-applied;
  - got_reset while the command in force is a reset; a wrong target or action is rejected and
    shown in error_list for one timeout.

What it does not do: answer a command at once. The State goes out on the next tick of the rate
loop, so the echo comes up to one period late (conformance.yaml next to this file says so).

--layout hub gives the hub layout instead (/<hub>/command DockEcuCommand with the node's fragment,
/<hub>/state DockEcuState with the node's State), bridged by dock_bridge_hub_layout.yaml.

Its slot sensors are the simulated station's: /sim/input sets them and /sim/<hub>/signals shows
them, as a hubd on the simulation board does (firmware/sim/README.md). Run it bridged by hubbridge
(dock_bridge.yaml) on a ROS 1 master: ROS_MASTER_URI=http://127.0.0.1:PORT dock_ecu_ros1.py
"""
import argparse
import os
import sys
import threading

import rospy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ros1_msgs  # noqa: E402  (next to this file)

DockState = ros1_msgs.message_class("hub_msgs/DockState")
DockCommand = ros1_msgs.message_class("hub_msgs/DockCommand")
DockSlot = ros1_msgs.message_class("hub_msgs/DockSlot")
SimInput = ros1_msgs.message_class("hub_msgs/SimInput")
SimSignals = ros1_msgs.message_class("hub_msgs/SimSignals")
SimSignal = ros1_msgs.message_class("hub_msgs/SimSignal")
DockEcuState = ros1_msgs.message_class("hub_msgs/DockEcuState")
DockEcuCommand = ros1_msgs.message_class("hub_msgs/DockEcuCommand")

LIFECYCLE_SAFE = 2
LIFECYCLE_OPERATIONAL = 3


class Tracker:
    """The command semantics of one node or of the hub level (firmware/runtime command_tracker.h)."""

    def __init__(self, timeout, name):
        self.timeout, self.name = timeout, name
        self.echo = None  # the content in force, or last in force
        self.in_force = False
        self.took_effect_at = None
        self.last_arrival = None
        self.rejection = None  # (text, time)

    def arrive(self, content, at, problem):
        """A command arrived at `at`; `problem` says why it is invalid (None: valid). True when valid."""
        if problem:
            self.rejection = (problem, at)
            return False
        if not self.in_force or content != self.echo:
            self.echo = content
            self.took_effect_at = at
            self.rejection = None
        self.in_force = True
        self.last_arrival = at
        return True

    def check(self, now):
        if self.in_force and now - self.last_arrival > self.timeout:
            self.in_force = False
            rospy.logwarn("%s: no valid command for more than %.3f s", self.name, self.timeout)

    def fill(self, state, now, is_reset):
        """The common State fields: header lifecycle, fresh_msg, t_plus, got_reset, error_list."""
        errors = []
        if self.rejection and now - self.rejection[1] <= self.timeout:
            errors.append("rejected command: " + self.rejection[0])
        if self.echo is not None and not self.in_force:
            errors.append("command timeout: no valid command for %.2f s (limit %.2f s); outputs in safe state"
                          % (now - self.last_arrival, self.timeout))
        state.header.lifecycle = LIFECYCLE_OPERATIONAL if self.in_force else LIFECYCLE_SAFE
        state.fresh_msg = self.in_force
        state.t_plus = now - self.took_effect_at if self.took_effect_at is not None else 0.0
        state.got_reset = self.in_force and is_reset
        state.error_list = errors


def copy_command(source, target):
    target.target_type, target.target_name, target.action = source.target_type, source.target_name, source.action


class DockEcu:
    def __init__(self, args):
        self.args = args
        self.lock = threading.Lock()
        self.inbox = []  # (command message, arrival time) from the callback thread
        self.occupied = {slot: False for slot in args.slots}
        self.node = Tracker(args.command_timeout, args.node)
        self.hub = Tracker(args.command_timeout, args.hub)
        self.seq = 0
        if args.layout == "hub":
            self.state_pub = rospy.Publisher("/%s/state" % args.hub, DockEcuState, queue_size=10)
            rospy.Subscriber("/%s/command" % args.hub, DockEcuCommand, self.on_command, queue_size=10)
        else:
            self.state_pub = rospy.Publisher(args.state_topic, DockState, queue_size=10)
            rospy.Subscriber(args.command_topic, DockCommand, self.on_command, queue_size=10)
        self.signals_pub = rospy.Publisher("/sim/%s/signals" % args.hub, SimSignals, queue_size=10)
        rospy.Subscriber("/sim/input", SimInput, self.on_sim_input, queue_size=50)

    def on_command(self, msg):
        with self.lock:
            self.inbox.append((msg, rospy.get_time()))

    def on_sim_input(self, msg):
        prefix = self.args.signal_prefix
        if msg.hub != self.args.hub or not msg.signal.startswith(prefix):
            return
        slot = msg.signal[len(prefix):]
        with self.lock:
            if slot in self.occupied:
                self.occupied[slot] = bool(msg.active)

    def node_command(self, msg, at):
        content = (msg.target_type, msg.target_name, msg.action)
        problem = None
        if msg.target_type != "dock" or msg.target_name != self.args.node:
            problem = ("wrong target: '%s' of type '%s' (this is '%s' of type 'dock')"
                       % (msg.target_name, msg.target_type, self.args.node))
        elif msg.action not in ("monitor", "reset"):
            problem = "unknown action '%s' (one of: monitor, reset)" % msg.action
        self.node.arrive(content, at, problem)

    def hub_command(self, msg, at):
        # hub_api/hub_layout.h: the hub command is checked and tracked; then its fragment goes to
        # the node, with an empty target_type/target_name meaning this node.
        content = (msg.target_type, msg.target_name, msg.action, msg.dock.target_type, msg.dock.target_name,
                   msg.dock.action)
        problem = None
        if msg.target_type != "dock_ecu" or msg.target_name != self.args.hub:
            problem = ("wrong target: '%s' of type '%s' (this is '%s' of type 'dock_ecu')"
                       % (msg.target_name, msg.target_type, self.args.hub))
        elif msg.action not in ("apply", "reset"):
            problem = "unknown action '%s' (one of: apply, reset)" % msg.action
        if not self.hub.arrive(content, at, problem):
            return
        fragment = DockCommand()
        copy_command(msg.dock, fragment)
        fragment.target_type = fragment.target_type or "dock"
        fragment.target_name = fragment.target_name or self.args.node
        self.node_command(fragment, at)
        self.hub_echo = msg

    def node_state(self, now):
        state = DockState()
        state.header.stamp = rospy.Time.from_sec(now)
        state.header.seq = self.seq
        state.name = self.args.node
        if self.node.echo is not None:
            state.echo.target_type, state.echo.target_name, state.echo.action = self.node.echo
        self.node.fill(state, now, self.node.echo is not None and self.node.echo[2] == "reset")
        with self.lock:
            occupied = dict(self.occupied)
        state.slots = [DockSlot(name=slot, occupied=occupied[slot]) for slot in self.args.slots]
        return state, occupied

    def cycle(self, now):
        with self.lock:
            arrived, self.inbox = self.inbox, []
        for msg, at in arrived:
            (self.hub_command if self.args.layout == "hub" else self.node_command)(msg, at)
        self.node.check(now)
        self.hub.check(now)
        self.seq += 1
        node_state, occupied = self.node_state(now)
        if self.args.layout == "hub":
            state = DockEcuState(name=self.args.hub, dock=node_state)
            state.header.stamp = node_state.header.stamp
            state.header.seq = self.seq
            if self.hub.echo is not None:
                copy_command(self.hub_echo, state.echo)
                copy_command(self.hub_echo.dock, state.echo.dock)
            self.hub.fill(state, now, self.hub.echo is not None and self.hub.echo[2] == "reset")
        else:
            state = node_state
        self.state_pub.publish(state)
        signals = SimSignals(hub=self.args.hub, valves=[], lifts=[])
        signals.signals = [SimSignal(name=self.args.signal_prefix + slot, output=False, active=occupied[slot])
                           for slot in self.args.slots]
        self.signals_pub.publish(signals)

    def spin(self):
        rate = rospy.Rate(self.args.rate)
        while not rospy.is_shutdown():
            self.cycle(rospy.get_time())
            try:
                rate.sleep()
            except rospy.ROSInterruptException:
                break


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--hub", default="dock_ecu")
    parser.add_argument("--layout", choices=("node_type", "hub"), default="node_type",
                        help="node_type: /dock/command, /<hub>/dock/state; hub: /<hub>/command, /<hub>/state")
    parser.add_argument("--node", default="dock")
    parser.add_argument("--state-topic", default="/dock_ecu/dock/state")
    parser.add_argument("--command-topic", default="/dock/command")
    parser.add_argument("--rate", type=float, default=10.0)
    parser.add_argument("--command-timeout", type=float, default=1.0)
    parser.add_argument("--signal-prefix", default="dock.slot.")
    parser.add_argument("--slots", nargs="+", default=["ladder_frame_tool", "filter_tool", "smart_tool", "spare"])
    args = parser.parse_args(rospy.myargv()[1:])
    rospy.init_node("dock_ecu_ros1", anonymous=True, disable_signals=False)
    DockEcu(args).spin()


if __name__ == "__main__":
    main()
