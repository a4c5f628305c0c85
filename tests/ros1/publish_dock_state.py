#!/usr/bin/python3
"""Publishes DockStates on /dock_ecu/dock/state at 10 Hz the way a ROS 1 team's node would, with
message classes built from --msg-dir (a copy of the tier's ROS 1 .msg files another team may have
changed) and
the node name given by --name (over its bound to test that the bridge drops it)."""
import argparse
import os
import sys

import rospy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ros1_msgs  # noqa: E402


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--msg-dir", default=ros1_msgs.MSG_DIR)
    parser.add_argument("--name", default="dock")
    args = parser.parse_args(rospy.myargv()[1:])
    DockState = ros1_msgs.message_class("hub_msgs/DockState", args.msg_dir)
    rospy.init_node("other_dock", anonymous=True)
    publisher = rospy.Publisher("/dock_ecu/dock/state", DockState, queue_size=10)
    rate = rospy.Rate(10)
    seq = 0
    while not rospy.is_shutdown():
        seq += 1
        state = DockState()
        state.header.seq = seq
        state.header.stamp = rospy.Time.now()
        state.name = args.name
        publisher.publish(state)
        try:
            rate.sleep()
        except rospy.ROSInterruptException:
            break


if __name__ == "__main__":
    main()
