# cmake -DROOT=<hubrt source dir> -DREGISTERED=<hub_msgs_registered.txt> -P check_ros2_package.cmake
# The ROS 2 package ros2/hub_msgs must gather exactly the hub_msgs .msg files hubrt builds its
# types from: what its glob finds (ros2/hub_msgs/hub_msgs_files.cmake) against the files of every
# registered message target (written by the build). A .msg in a hub folder that no
# hubrt_add_messages() lists, or a hub_msgs type kept outside the globbed folders, fails here by name.
cmake_minimum_required(VERSION 3.25)
include("${ROOT}/ros2/hub_msgs/hub_msgs_files.cmake")
hub_msgs_msg_files(globbed "${ROOT}")
file(STRINGS "${REGISTERED}" registered)
list(SORT registered)
set(problems "")
foreach(file IN LISTS globbed)
  if(NOT file IN_LIST registered)
    string(APPEND problems "\n  ${file}: in the ROS 2 package, but no registered hubrt_add_messages() target lists it")
  endif()
endforeach()
foreach(file IN LISTS registered)
  if(NOT file IN_LIST globbed)
    string(APPEND problems "\n  ${file}: a hub_msgs type hubrt builds, outside the folders the ROS 2 package gathers "
                           "(ros2/hub_msgs/hub_msgs_files.cmake)")
  endif()
endforeach()
list(LENGTH globbed count)
if(count LESS 40)
  string(APPEND problems "\n  only ${count} .msg files found under ${ROOT}: expected every hub's")
endif()
if(problems)
  message(FATAL_ERROR "ros2/hub_msgs and hubrt's message targets differ:${problems}")
endif()
message(STATUS "ros2/hub_msgs gathers the ${count} hub_msgs .msg files hubrt builds")
