// Cyclone's key-to-instance map of a sertype's domain, for serdata_pool.cc. In C: Cyclone's
// ddsi_domaingv.h, which defines the domain, does not compile as C++ (q_sockwaitset.h declares a
// typedef with its struct's own name).
#pragma once

#include <dds/dds.h>
#include <dds/ddsi/ddsi_serdata.h>
#include <dds/ddsi/ddsi_tkmap.h>

#ifdef __cplusplus
extern "C" {
#endif

// Looks the instance of `serdata` up in the key-to-instance map of the domain `sertype` is
// registered with, creating it when absent, and returns it with a reference for the caller
// (ddsi_tkmap_lookup_instance_ref, with the calling thread made awake as Cyclone's own callers
// do, dds_instance.c). NULL when the sertype belongs to no domain.
struct ddsi_tkmap_instance* hubrt_dds_instance_ref(const struct ddsi_sertype* sertype,
                                                   struct ddsi_serdata* serdata);

// Drops a reference taken by hubrt_dds_instance_ref. Precondition: the domain still exists.
void hubrt_dds_instance_unref(const struct ddsi_sertype* sertype, struct ddsi_tkmap_instance* instance);

#ifdef __cplusplus
}
#endif
