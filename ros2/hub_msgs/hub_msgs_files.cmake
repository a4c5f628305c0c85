# The .msg files of the ROS 2 package hub_msgs in a hubrt source tree: each lives with the code
# that uses it — every hub type's hubs/<hub>/msg/*.msg, the common StateHeader
# (firmware/msgs/msg/), the simulation's (firmware/sim/msg/) and the operator screen's
# (firmware/hubctl/msg/) — so a new hub type adds its folder and nothing here. Plain CMake, no
# hubrt or ROS code: included by this package's CMakeLists.txt (colcon) and by hubrt's build, whose
# test hubrt_ros2_hub_msgs_holds_every_type checks that the set is the hub_msgs types hubrt builds.

# hub_msgs_msg_files(<out> <hubrt source dir>): the absolute paths, sorted.
function(hub_msgs_msg_files out root)
  set(globs "${root}/hubs/*/msg/*.msg" "${root}/firmware/msgs/msg/*.msg" "${root}/firmware/sim/msg/*.msg"
      "${root}/firmware/hubctl/msg/*.msg")
  if(CMAKE_SCRIPT_MODE_FILE)
    file(GLOB files ${globs})
  else()
    file(GLOB files CONFIGURE_DEPENDS ${globs})  # a new .msg configures the package again
  endif()
  list(SORT files)
  set(${out} ${files} PARENT_SCOPE)
endfunction()

# hub_msgs_interface_tuples(<out> <hubrt source dir>): the same files as rosidl_generate_interfaces()
# takes files outside the package folder: "<absolute base>:msg/<Type>.msg" (rosidl_cmake,
# rosidl_generate_interfaces.cmake: "a tuple separated by a colon with an absolute base path and a
# path relative to that base path"; the folder "msg" makes it a message).
function(hub_msgs_interface_tuples out root)
  hub_msgs_msg_files(files "${root}")
  set(tuples "")
  foreach(file IN LISTS files)
    get_filename_component(msg_dir "${file}" DIRECTORY)
    get_filename_component(base "${msg_dir}" DIRECTORY)
    get_filename_component(name "${file}" NAME)
    list(APPEND tuples "${base}:msg/${name}")
  endforeach()
  set(${out} ${tuples} PARENT_SCOPE)
endfunction()
