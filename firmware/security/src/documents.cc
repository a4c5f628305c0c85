#include "hubrt/security/documents.h"

#include <fmt/format.h>

#include "openssl_util.h"

namespace hubrt::security {
namespace {

std::string id_range_xml(std::uint32_t first, std::uint32_t last) {
  return first == last ? fmt::format("<id>{}</id>", first)
                       : fmt::format("<id_range><min>{}</min><max>{}</max></id_range>", first, last);
}

// Every covered domain, or `ids` (ascending, each once) with runs of consecutive ids as ranges.
std::string domains_xml(const std::vector<std::uint32_t>& ids = {}) {
  if (ids.empty())
    return "<domains>" +
           id_range_xml(static_cast<std::uint32_t>(kFirstDomainId),
                        static_cast<std::uint32_t>(kLastDomainId)) +
           "</domains>";
  std::string xml = "<domains>";
  for (std::size_t i = 0; i < ids.size();) {
    std::size_t j = i;
    while (j + 1 < ids.size() && ids[j + 1] == ids[j] + 1) ++j;
    xml += id_range_xml(ids[i], ids[j]);
    i = j + 1;
  }
  return xml + "</domains>";
}

std::string topic_rule(const std::string& expression) {
  return fmt::format(
      "      <topic_rule>\n"
      "        <topic_expression>{}</topic_expression>\n"
      "        <enable_discovery_protection>true</enable_discovery_protection>\n"
      "        <enable_liveliness_protection>true</enable_liveliness_protection>\n"
      "        <enable_read_access_control>true</enable_read_access_control>\n"
      "        <enable_write_access_control>true</enable_write_access_control>\n"
      "        <metadata_protection_kind>NONE</metadata_protection_kind>\n"
      "        <data_protection_kind>ENCRYPT</data_protection_kind>\n"
      "      </topic_rule>\n",
      xml_escape(expression));
}

std::string topics_xml(const char* element, const std::vector<std::string>& topics) {
  if (topics.empty()) return {};
  std::string text = fmt::format("        <{}><topics>\n", element);
  for (const std::string& topic : topics)
    text += fmt::format("          <topic>{}</topic>\n", xml_escape(topic));
  text += fmt::format("        </topics></{}>\n", element);
  return text;
}

}  // namespace

std::string xml_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string governance_xml() {
  // The first rule whose expression matches a topic applies (access_control.c:
  // get_topic_sec_attributes walks the rules in order); all hubrt's rules say the same, they are
  // listed so that a reader of the document sees which topics the station has.
  std::string rules;
  for (const char* expression : {"rt/*/command", "rt/*/state", "rt/diagnostics", "rt/sim/*", "*"}) {
    rules += topic_rule(expression);
  }
  return fmt::format(
      "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
      "<!-- hubrt station governance, made by `hubctl security init` -->\n"
      "<dds xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\"\n"
      "     xsi:noNamespaceSchemaLocation=\"http://www.omg.org/spec/DDS-SECURITY/20170901/"
      "omg_shared_ca_governance.xsd\">\n"
      "  <domain_access_rules>\n"
      "    <domain_rule>\n"
      "      {}\n"
      "      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>\n"
      "      <enable_join_access_control>true</enable_join_access_control>\n"
      "      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>\n"
      "      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>\n"
      "      <rtps_protection_kind>NONE</rtps_protection_kind>\n"
      "      <topic_access_rules>\n"
      "{}"
      "      </topic_access_rules>\n"
      "    </domain_rule>\n"
      "  </domain_access_rules>\n"
      "</dds>\n",
      domains_xml(), rules);
}

std::string permissions_xml(const Grant& grant) {
  return fmt::format(
      "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
      "<!-- hubrt permissions, made by `hubctl security add` -->\n"
      "<dds xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\"\n"
      "     xsi:noNamespaceSchemaLocation=\"http://www.omg.org/spec/DDS-SECURITY/20170901/"
      "omg_shared_ca_permissions.xsd\">\n"
      "  <permissions>\n"
      "    <grant name=\"{}\">\n"
      "      <subject_name>{}</subject_name>\n"
      "      <validity><not_before>{}</not_before><not_after>{}</not_after></validity>\n"
      "      <allow_rule>\n"
      "        {}\n"
      "{}{}"
      "      </allow_rule>\n"
      "      <default>DENY</default>\n"
      "    </grant>\n"
      "  </permissions>\n"
      "</dds>\n",
      xml_escape(grant.name), xml_escape(grant.subject), detail::iso8601_utc(grant.not_before_unix),
      detail::iso8601_utc(grant.not_after_unix), domains_xml(grant.domains),
      topics_xml("publish", grant.publish), topics_xml("subscribe", grant.subscribe));
}

}  // namespace hubrt::security
