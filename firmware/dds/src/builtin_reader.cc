#include "builtin_reader.h"

#include "hubrt/dds/retcode.h"

#include "listener.h"

namespace hubrt::dds::detail {

Expected<EntityHandle> listening_builtin_reader(const Participant& participant, dds_entity_t topic,
                                                const char* name, const std::string& what, void* arg,
                                                dds_on_data_available_fn callback) {
  const ListenerPtr listener(dds_create_listener(arg));
  dds_lset_data_available(listener.get(), callback);
  EntityHandle reader(dds_create_reader(participant.handle(), topic, nullptr, listener.get()));
  if (reader.get() < 0) return dds_error(reader.get(), what + ": read discovery topic " + name);
  return reader;
}

}  // namespace hubrt::dds::detail
