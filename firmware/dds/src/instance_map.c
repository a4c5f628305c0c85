#include "instance_map.h"

#include <dds/ddsi/ddsi_domaingv.h>
#include <dds/ddsi/q_thread.h>

// Set when the sertype was registered with its domain (ddsi_sertype.h, `gv`).
static struct ddsi_domaingv* domain_of(const struct ddsi_sertype* sertype) {
  return (struct ddsi_domaingv*)ddsrt_atomic_ldvoidp(&sertype->gv);
}

struct ddsi_tkmap_instance* hubrt_dds_instance_ref(const struct ddsi_sertype* sertype,
                                                   struct ddsi_serdata* serdata) {
  struct ddsi_domaingv* gv = domain_of(sertype);
  if (gv == NULL) return NULL;
  struct thread_state* const thread = lookup_thread_state();
  thread_state_awake(thread, gv);
  struct ddsi_tkmap_instance* instance = ddsi_tkmap_lookup_instance_ref(gv->m_tkmap, serdata);
  thread_state_asleep(thread);
  return instance;
}

void hubrt_dds_instance_unref(const struct ddsi_sertype* sertype, struct ddsi_tkmap_instance* instance) {
  struct ddsi_domaingv* gv = domain_of(sertype);
  if (gv == NULL) return;
  struct thread_state* const thread = lookup_thread_state();
  thread_state_awake(thread, gv);
  ddsi_tkmap_instance_unref(gv->m_tkmap, instance);
  thread_state_asleep(thread);
}
