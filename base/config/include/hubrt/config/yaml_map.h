// Typed, located access to YAML mappings. Every error names the file, the line and column, the
// key and what is wrong, e.g. "boards/rpi4-dock-ecu.yaml:14:9: inputs.slot0.line: expected an
// integer in [0, 511], got 'five'".
#pragma once

#include <cstdint>
#include <initializer_list>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "hubrt/base/status.h"

namespace hubrt::config {

class YamlMap {
 public:
  // Parses a file whose top level must be a mapping. Errors name the file (and the line for syntax
  // errors). The file must be a regular file (require_regular_file: kNotFound when it does not
  // exist; a directory or a symbolic link loop says so) of at most 1 MiB (kInvalidArgument,
  // unread beyond that), and the document must pass the checks of load_string.
  static Expected<YamlMap> load_file(const std::string& path);
  // Same, for text already in memory; `name` stands in for the file name in messages. Refused
  // (kInvalidArgument, located at file:line:column): text that is not strict UTF-8 (RFC 3629,
  // anywhere, comments included), a YAML syntax error, a top level that is not a mapping, and a
  // mapping anywhere in the document that has the same key twice (yaml-cpp would keep both and
  // every look-up would see only the first).
  static Expected<YamlMap> load_string(const std::string& text, const std::string& name);

  [[nodiscard]] const std::string& file() const { return *file_; }
  // Dotted path of this mapping from the document root, e.g. "nodes[1].slots".
  [[nodiscard]] const std::string& path() const { return path_; }
  [[nodiscard]] const YAML::Node& node() const { return node_; }

  [[nodiscard]] bool has(std::string_view key) const;
  [[nodiscard]] std::vector<std::string> keys() const;

  // Fails on any key not in `allowed`, suggesting what is allowed.
  Expected<void> only_keys(std::initializer_list<std::string_view> allowed) const;

  Expected<std::string> string(std::string_view key) const;
  Expected<std::string> string_or(std::string_view key, std::string fallback) const;
  Expected<std::int64_t> integer(std::string_view key, std::int64_t min, std::int64_t max) const;
  Expected<std::int64_t> integer_or(std::string_view key, std::int64_t fallback, std::int64_t min,
                                    std::int64_t max) const;
  Expected<double> number(std::string_view key, double min, double max) const;
  Expected<double> number_or(std::string_view key, double fallback, double min, double max) const;
  Expected<bool> boolean(std::string_view key) const;
  Expected<bool> boolean_or(std::string_view key, bool fallback) const;
  // One of `choices`, e.g. layout: node_type | hub.
  Expected<std::string> choice(std::string_view key, std::initializer_list<std::string_view> choices) const;
  Expected<std::string> choice_or(std::string_view key, std::string fallback,
                                  std::initializer_list<std::string_view> choices) const;

  Expected<YamlMap> map(std::string_view key) const;
  // A mapping of name -> mapping, in file order.
  Expected<std::vector<std::pair<std::string, YamlMap>>> named_maps(std::string_view key) const;
  // A sequence of mappings. An absent key gives an empty list when `optional`.
  Expected<std::vector<YamlMap>> list_of_maps(std::string_view key, bool optional = false) const;
  Expected<std::vector<std::string>> list_of_strings(std::string_view key, bool optional = false) const;

  // An error located at this mapping, or at one of its keys (its value's position).
  [[nodiscard]] Error error(std::string_view message) const;
  [[nodiscard]] Error error_at(std::string_view key, std::string_view message) const;

 private:
  YamlMap(std::shared_ptr<const std::string> file, const YAML::Node& node, std::string path);
  [[nodiscard]] std::string key_path(std::string_view key) const;
  [[nodiscard]] Error located(const YAML::Mark& mark, std::string_view what, std::string_view message) const;
  Expected<YAML::Node> scalar(std::string_view key) const;

  std::shared_ptr<const std::string> file_;
  YAML::Node node_;
  std::string path_;
};

}  // namespace hubrt::config
