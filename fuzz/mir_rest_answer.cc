// What a MiR100 answers over its REST API, through the hub's decoder (protocols/mir_rest): any
// bytes as the body of an answer to each request the hub sends, under each HTTP status class.
// Nothing may throw or crash; a reply is either understood (ok) or says why not.
//
// Input: byte 0 picks the request (which fields the decoder reads), byte 1 the HTTP status (200,
// 201, 204, 401, 500), the rest is the body.
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "hubrt/protocol/mir_rest.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace mir = hubrt::protocol::mir;
  if (size < 2) return 0;
  const std::array<hubrt::hal::HttpRequest, 8> requests = {
      mir::get_status(),
      mir::set_state(mir::kStatePause),
      mir::clear_error(),
      mir::find_position("home"),
      mir::post_position("here", 1.0F, 2.0F, 90.0F, "5d2f-01"),
      mir::post_mission("a1-b2", "Position", "00-01"),
      mir::get_mission(7),
      mir::clear_queue()};
  constexpr std::array<int, 5> kStatuses = {200, 201, 204, 401, 500};
  hubrt::hal::HttpResponse response;
  response.status = kStatuses[data[1] % kStatuses.size()];
  response.body.assign(reinterpret_cast<const char*>(data + 2), size - 2);  // NOLINT: libFuzzer's bytes
  mir::MirReply reply;
  mir::decode_reply(requests[data[0] % requests.size()], response, reply);
  if (!reply.ok && reply.problem.empty()) std::abort();  // a failure always says why
  return 0;
}
