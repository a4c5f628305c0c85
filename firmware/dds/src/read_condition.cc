#include "hubrt/dds/read_condition.h"

#include <string>

#include "hubrt/dds/retcode.h"

namespace hubrt::dds {

Expected<ReadCondition> ReadCondition::create(const UntypedReader& reader, std::uint32_t mask) {
  const dds_entity_t handle = dds_create_readcondition(reader.handle(), mask);
  if (handle < 0) return dds_error(handle, "create read condition on '" + reader.topic_name() + "'");
  return ReadCondition(EntityHandle(handle));
}

}  // namespace hubrt::dds
