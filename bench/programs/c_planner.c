/* An independent planner for the tails bench (bench/programs/tails.cc, issue 33 point 1): plain C
 * on Cyclone's C API, in its own process, sharing no code with the bench's own planner, so that a
 * tail seen by both is not an artefact of one planner. Like the bench's planner it commands the
 * Dock ECU (rt/dock/command -> rt/dock_ecu/dock/state) and the raw pong (rt/bench/ping ->
 * rt/bench/pong) with DockCommands alternating "monitor" and "reset", hub and raw taking turns in
 * an alternating order, and waits for the State echoing each:
 *   sparse        N commands per side, each pair followed by a gap drawn from 20-120 ms;
 *   back to back  bursts of B round trips per side (the first of each unrecorded: it comes after a
 *                 pause), R ms of pause after each pair of bursts for the hub's budget of immediate
 *                 States to refill, until N are recorded per side.
 * Prints one line per recorded round trip on stdout,
 *   <regime> <side> <sent_ns> <echo_ns> <other_state_between>
 * (CLOCK_MONOTONIC, the clock of `hubd --trace-stages`), "lost <regime> <side>" for a command
 * without an echo within a second (regime "warmup" before recording), and "done" at the end. Domain from
 * ROS_DOMAIN_ID, configuration from CYCLONEDDS_URI; QoS as every raw peer of the bench (reliable, volatile,
 * keep-last 10, XCDR1). hubrt_bench_c_planner SPARSE BACK_TO_BACK BURST REFILL_MS SEED
 */
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <dds/dds.h>

#include "dock.h"

struct peer {
  const char* side;
  dds_entity_t writer;
  dds_entity_t reader;
  dds_entity_t waitset;
  unsigned long sent;
};

static int64_t mono_ns(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (int64_t)ts.tv_sec * 1000000000LL + ts.tv_nsec;
}

static void pause_ns(int64_t ns) {
  struct timespec ts = {(time_t)(ns / 1000000000LL), (long)(ns % 1000000000LL)};
  while (nanosleep(&ts, &ts) != 0 && errno == EINTR) {
  }
}

static dds_qos_t* bench_qos(void) {
  dds_qos_t* qos = dds_create_qos();
  const dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
  dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
  dds_qset_durability(qos, DDS_DURABILITY_VOLATILE);
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, 10);
  dds_qset_data_representation(qos, 1, &xcdr1);
  return qos;
}

/* 0 on success; says what failed on stderr otherwise. */
static int open_peer(dds_entity_t participant, struct peer* p, const char* side, const char* command_topic,
                     const char* state_topic) {
  dds_qos_t* qos = bench_qos();
  const dds_entity_t commands =
      dds_create_topic(participant, &hub_msgs_msg_dds__DockCommand__desc, command_topic, qos, NULL);
  const dds_entity_t states =
      dds_create_topic(participant, &hub_msgs_msg_dds__DockState__desc, state_topic, qos, NULL);
  memset(p, 0, sizeof *p);
  p->side = side;
  if (commands >= 0 && states >= 0) {
    p->writer = dds_create_writer(participant, commands, qos, NULL);
    p->reader = dds_create_reader(participant, states, qos, NULL);
  }
  dds_delete_qos(qos);
  if (commands < 0 || states < 0 || p->writer < 0 || p->reader < 0) {
    fprintf(stderr, "c_planner: cannot open %s (%s -> %s)\n", side, command_topic, state_topic);
    return -1;
  }
  p->waitset = dds_create_waitset(participant);
  dds_waitset_attach(p->waitset, dds_create_readcondition(p->reader, DDS_ANY_STATE), 0);
  /* Up to 20 s for the answering process to read the commands (discovery). */
  for (int i = 0; i < 2000; ++i) {
    dds_publication_matched_status_t matched;
    if (dds_get_publication_matched_status(p->writer, &matched) == 0 && matched.current_count > 0) return 0;
    pause_ns(10000000LL);
  }
  fprintf(stderr, "c_planner: nobody reads %s\n", command_topic);
  return -1;
}

static void drain(const struct peer* p) {
  void* samples[8] = {0};
  dds_sample_info_t infos[8];
  dds_return_t n;
  while ((n = dds_take(p->reader, samples, infos, 8, 8)) > 0) dds_return_loan(p->reader, samples, n);
}

/* One command out until the State echoing it is back; prints it when `regime` is not NULL. */
static void round_trip(struct peer* p, const char* regime) {
  const char* action = p->sent++ % 2 == 0 ? "monitor" : "reset";
  hub_msgs_msg_dds__DockCommand_ command;
  int other_between = 0;
  memset(&command, 0, sizeof command);
  snprintf(command.target_type, sizeof command.target_type, "%s", "dock");
  snprintf(command.target_name, sizeof command.target_name, "%s", "dock");
  snprintf(command.action, sizeof command.action, "%s", action);
  drain(p);
  const int64_t sent = mono_ns();
  if (dds_write(p->writer, &command) < 0) {
    printf("lost %s %s\n", regime != NULL ? regime : "warmup", p->side);
    return;
  }
  for (;;) {
    dds_attach_t fired = 0;
    if (dds_waitset_wait(p->waitset, &fired, 1, DDS_SECS(1)) <= 0) {
      printf("lost %s %s\n", regime != NULL ? regime : "warmup", p->side);
      return;
    }
    const int64_t woke = mono_ns();
    void* samples[8] = {0};
    dds_sample_info_t infos[8];
    const dds_return_t n = dds_take(p->reader, samples, infos, 8, 8);
    int echoed = 0;
    for (dds_return_t i = 0; i < n; ++i) {
      const hub_msgs_msg_dds__DockState_* state = samples[i];
      if (!infos[i].valid_data) continue;
      if (strcmp(state->echo.action, action) == 0) {
        echoed = 1;
      } else {
        other_between = 1;
      }
    }
    if (n > 0) dds_return_loan(p->reader, samples, n);
    if (echoed) {
      if (regime != NULL)
        printf("%s %s %lld %lld %d\n", regime, p->side, (long long)sent, (long long)woke, other_between);
      return;
    }
  }
}

static long parse_count(const char* text, const char* what) {
  char* end = NULL;
  errno = 0;
  const long value = strtol(text, &end, 10);
  if (errno != 0 || end == text || *end != '\0' || value < 0 || value > 1000000) {
    fprintf(stderr, "c_planner: %s wants a count from 0 to 1000000, not '%s'\n", what, text);
    exit(2); /* NOLINT(concurrency-mt-unsafe): before any thread */
  }
  return value;
}

int main(int argc, char** argv) {
  if (argc != 6) {
    fprintf(stderr, "usage: %s SPARSE BACK_TO_BACK BURST REFILL_MS SEED\n", argv[0]);
    return 2;
  }
  const long sparse = parse_count(argv[1], "SPARSE");
  const long back_to_back = parse_count(argv[2], "BACK_TO_BACK");
  const long burst = parse_count(argv[3], "BURST");
  const long refill_ms = parse_count(argv[4], "REFILL_MS");
  unsigned int seed = (unsigned int)parse_count(argv[5], "SEED");
  if (burst < 2) {
    fprintf(stderr, "c_planner: BURST wants at least 2 (the first of each burst is not recorded)\n");
    return 2;
  }
  const char* domain_text = getenv("ROS_DOMAIN_ID"); /* NOLINT(concurrency-mt-unsafe): before any thread */
  const dds_domainid_t domain =
      domain_text != NULL ? (dds_domainid_t)parse_count(domain_text, "ROS_DOMAIN_ID") : 0;
  const dds_entity_t participant = dds_create_participant(domain, NULL, NULL);
  if (participant < 0) {
    fprintf(stderr, "c_planner: no participant in domain %u: %s\n", (unsigned)domain,
            dds_strretcode(participant));
    return 1;
  }
  struct peer peers[2];
  if (open_peer(participant, &peers[0], "raw", "rt/bench/ping", "rt/bench/pong") != 0 ||
      open_peer(participant, &peers[1], "hub", "rt/dock/command", "rt/dock_ecu/dock/state") != 0) {
    dds_delete(participant);
    return 1;
  }
  /* Warm-up: matched both ways, caches filled. */
  for (int i = 0; i < 20; ++i) {
    round_trip(&peers[0], NULL);
    round_trip(&peers[1], NULL);
    pause_ns(refill_ms * 1000000LL);
  }
  for (long i = 0; i < sparse; ++i) {
    const int first = (int)(i % 2);
    round_trip(&peers[first], "sparse");
    round_trip(&peers[1 - first], "sparse");
    pause_ns((20 + (int64_t)(rand_r(&seed) % 101)) * 1000000LL);
  }
  for (long recorded = 0, round = 0; recorded < back_to_back; recorded += burst - 1, ++round) {
    const int first = (int)(round % 2);
    for (int k = 0; k < 2; ++k) {
      struct peer* p = &peers[k == 0 ? first : 1 - first];
      round_trip(p, NULL);
      for (long j = 1; j < burst; ++j) round_trip(p, "back_to_back");
    }
    pause_ns(refill_ms * 1000000LL);
  }
  printf("done\n");
  fflush(stdout);
  dds_delete(participant);
  return 0;
}
