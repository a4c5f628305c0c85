"""ROS 1 message classes for the hub types, built the way rosbag builds classes it has no code
for: genmsg reads the ROS 1 .msg files (HUBRT_ROS1_MSG_DIR: written into the build tree by
`hubbridge --write-ros1-msgs` from the hub types' .msg when the tier starts, ros1_tier.py) and
computes the full definition and md5sum, genpy.dynamic makes the class. So the md5sum this side
announces is genmsg's own, computed independently of hubbridge."""
import os

import genmsg
import genmsg.gentools
import genmsg.msg_loader
import genpy.dynamic

# Set by ros1_tier.py for itself and every process it starts.
MSG_DIR = os.environ.get("HUBRT_ROS1_MSG_DIR", "")


def _context(msg_dir):
    search = {pkg: [os.path.join(msg_dir, pkg, "msg")] for pkg in os.listdir(msg_dir)}
    return genmsg.MsgContext.create_default(), search


def definition(type_name, msg_dir=MSG_DIR):
    """(full definition, md5sum) of `type_name`, e.g. "hub_msgs/DockState", per genmsg."""
    context, search = _context(msg_dir)
    spec = genmsg.msg_loader.load_msg_by_type(context, type_name, search)
    genmsg.msg_loader.load_depends(context, spec, search)
    return genmsg.gentools.compute_full_text(context, spec), genmsg.gentools.compute_md5(context, spec)


def message_class(type_name, msg_dir=MSG_DIR):
    """The genpy message class of `type_name`."""
    text, _ = definition(type_name, msg_dir)
    return genpy.dynamic.generate_dynamic(type_name, text)[type_name]


if __name__ == "__main__":
    # `ros1_msgs.py [DIR]`: "type md5sum" for every message in DIR, to compare with hubbridge's.
    import sys
    directory = sys.argv[1] if len(sys.argv) > 1 else MSG_DIR
    if not directory:
        sys.exit("ros1_msgs.py: give the ROS 1 .msg directory (or set HUBRT_ROS1_MSG_DIR)")
    for pkg in sorted(os.listdir(directory)):
        for name in sorted(os.listdir(os.path.join(directory, pkg, "msg"))):
            type_name = "%s/%s" % (pkg, name[:-4])
            print(type_name, definition(type_name, directory)[1])
