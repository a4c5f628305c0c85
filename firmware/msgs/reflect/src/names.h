/* Names of IDL declarations as the generated code spells them. C, because libcycloneddsidl's
 * headers do not compile as C++. */
#ifndef HUBRT_REFLECT_NAMES_H
#define HUBRT_REFLECT_NAMES_H

#include <stdbool.h>
#include <stddef.h>

/* Scoped name of a module-nested declaration, outermost first, joined by `sep`: "::" gives the
 * DDS type name ("hub_msgs::msg::dds_::DockState_"), "_" the C type name idlc generates
 * ("hub_msgs_msg_dds__DockState_"). False when it does not fit `size`. */
bool reflect_scoped_name(const void* node, const char* sep, char* buf, size_t size);

/* ROS 2 name of a DDS name that follows the ROS 2 mapping <pkg>::msg::dds_::<Type>_ (also srv,
 * action): "hub_msgs/msg/DockState". Empty string otherwise. False when it does not fit. */
bool reflect_ros_name(const char* dds_name, char* buf, size_t size);

/* `text` with every character that is not a letter or digit replaced by '_', and a leading '_'
 * if it starts with a digit — what CMake's string(MAKE_C_IDENTIFIER) does. */
bool reflect_c_identifier(const char* text, char* buf, size_t size);

/* File name without directories and without its last extension: "a/b/dock.idl" -> "dock". */
bool reflect_file_stem(const char* path, char* buf, size_t size);

/* File name without directories: "a/b/dock.idl" -> "dock.idl". */
const char* reflect_file_name(const char* path);

#endif
