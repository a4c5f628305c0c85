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

LIFECYCLE_SAFE = 2
LIFECYCLE_OPERATIONAL = 3
ACTIONS = ("monitor", "reset")


class DockEcu:
    def __init__(self, args):
        self.args = args
        self.lock = threading.Lock()
        self.inbox = []  # (command tuple, arrival time) from the callback thread
        self.occupied = {slot: False for slot in args.slots}
        self.echo = None  # (target_type, target_name, action) in force or last in force
        self.in_force = False
        self.took_effect_at = None
        self.last_arrival = None
        self.rejection = None  # (text, time)
        self.seq = 0
        self.state_pub = rospy.Publisher(args.state_topic, DockState, queue_size=10)
        self.signals_pub = rospy.Publisher("/sim/%s/signals" % args.hub, SimSignals, queue_size=10)
        rospy.Subscriber(args.command_topic, DockCommand, self.on_command, queue_size=10)
        rospy.Subscriber("/sim/input", SimInput, self.on_sim_input, queue_size=50)

    def on_command(self, msg):
        with self.lock:
            self.inbox.append(((msg.target_type, msg.target_name, msg.action), rospy.get_time()))

    def on_sim_input(self, msg):
        prefix = self.args.signal_prefix
        if msg.hub != self.args.hub or not msg.signal.startswith(prefix):
            return
        slot = msg.signal[len(prefix):]
        with self.lock:
            if slot in self.occupied:
                self.occupied[slot] = bool(msg.active)

    def take_commands(self):
        with self.lock:
            arrived, self.inbox = self.inbox, []
        for command, at in arrived:
            target_type, target_name, action = command
            if target_type != "dock" or target_name != self.args.node:
                self.rejection = ("wrong target: '%s' of type '%s' (this is '%s' of type 'dock')"
                                  % (target_name, target_type, self.args.node), at)
                continue
            if action not in ACTIONS:
                self.rejection = ("unknown action '%s' (one of: %s)" % (action, ", ".join(ACTIONS)), at)
                continue
            if not self.in_force or command != self.echo:
                self.echo = command
                self.took_effect_at = at
                self.rejection = None
            self.in_force = True
            self.last_arrival = at

    def cycle(self, now):
        self.take_commands()
        timeout = self.args.command_timeout
        if self.in_force and now - self.last_arrival > timeout:
            self.in_force = False
            rospy.logwarn("%s: no valid command for more than %.3f s", self.args.node, timeout)
        errors = []
        if self.rejection and now - self.rejection[1] <= timeout:
            errors.append("rejected command: " + self.rejection[0])
        if self.echo is not None and not self.in_force:
            errors.append("command timeout: no valid command for %.2f s (limit %.2f s); outputs in safe state"
                          % (now - self.last_arrival, timeout))
        state = DockState()
        self.seq += 1
        state.header.stamp = rospy.Time.from_sec(now)
        state.header.seq = self.seq
        state.header.lifecycle = LIFECYCLE_OPERATIONAL if self.in_force else LIFECYCLE_SAFE
        state.name = self.args.node
        if self.echo is not None:
            state.echo.target_type, state.echo.target_name, state.echo.action = self.echo
        state.fresh_msg = self.in_force
        state.t_plus = now - self.took_effect_at if self.took_effect_at is not None else 0.0
        state.got_reset = self.in_force and self.echo[2] == "reset"
        state.error_list = errors
        with self.lock:
            occupied = dict(self.occupied)
        state.slots = [DockSlot(name=slot, occupied=occupied[slot]) for slot in self.args.slots]
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
