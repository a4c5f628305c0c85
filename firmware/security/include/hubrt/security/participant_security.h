// What hubd, hubctl and hubsim do with `--security <dir> --identity <name>` (or a hub file's
// `security:` section): check the credentials themselves, so that an expired or foreign
// certificate is refused with a message that says so, then give Cyclone its <Security>
// configuration with the plugins Debian's Cyclone ships.
#pragma once

#include <cstdint>
#include <string>

#include "hubrt/base/status.h"
#include "hubrt/security/station_files.h"

namespace hubrt::security {

// Checks, at `now_unix`, everything Cyclone would refuse a participant for, in terms of the files:
// each file readable; both CA certificates valid now; the identity certificate issued by the
// identity CA and valid now (not yet valid / expired with the dates); the private key the
// certificate's; governance and permissions signed by the permissions CA (S/MIME).
// Errors: kFailedPrecondition for expired / not yet valid / untrusted / mismatched credentials,
// kNotFound / kPermissionDenied / kIo for unreadable files, kInvalidArgument for malformed ones;
// every message names the file.
Expected<void> check_credentials(const Credentials& files, std::int64_t now_unix);

// What a participant with these credentials is, for the messages that say its chain was checked
// and for the ones that say a peer did not authenticate it: "certificate O=...,CN=dock_ecu
// (<identity cert>, valid until <date>) of identity CA O=...,CN=... (<identity CA file>)". Only
// authenticates with peers whose identity CA is that one. Reads the two certificates; a file that
// cannot be read is named as such (check_credentials says why).
std::string describe_identity(const Credentials& files);

// The folder holding Debian's Cyclone security plugins (libddsc0debian's
// libdds_security_{auth,ac,crypto}.so): $HUBRT_DDS_SECURITY_PLUGINS when set, else the one
// under the library path of the architecture hubrt was built for
// (/usr/lib/<multiarch triplet>/libddsc0debian, from CMake's CMAKE_LIBRARY_ARCHITECTURE so that a
// cross build names the target's triplet). Reads the environment.
std::string plugin_folder();

// A Cyclone XML source (to be appended to the domain's configuration, after any other source)
// holding Domain/Security for `files`, with the three plugins loaded by full path from
// `plugins` (ddsrt_dlopen takes a name containing '/' as it is: src/ddsrt/src/dynlib/posix/
// dynlib.c). Element names: Cyclone 0.10.2 src/core/ddsi/include/dds/ddsi/ddsi_cfgelems.h,
// security_omg_config_elements. Errors: kNotFound when a plugin file is missing.
Expected<std::string> cyclone_security_xml(const Credentials& files, const std::string& plugins);

// check_credentials, then cyclone_security_xml with plugin_folder(): what a program appends to
// its Cyclone configuration. Reads the environment.
Expected<std::string> secure_participant_xml(const Credentials& files, std::int64_t now_unix);

}  // namespace hubrt::security

namespace hubrt::security {

// `dir` and `identity` as given to a program (--security/--identity or a hub file's security:).
struct SecurityChoice {
  std::string dir;
  std::string identity;
};

// check_identity_name, then secure_participant_xml for the identity's files in `dir`.
// Errors: as those, the message saying which identity was refused.
Expected<std::string> security_xml_for(const SecurityChoice& choice, std::int64_t now_unix);

// The Cyclone configuration sources to create a secured domain with: `cyclone_xml`, or when that
// is empty $CYCLONEDDS_URI (nothing when unset), followed by `security_xml` (Cyclone reads
// comma-separated sources in order). Reads the environment.
std::string with_security(const std::string& cyclone_xml, const std::string& security_xml);

}  // namespace hubrt::security
