/* SPDX-License-Identifier: MIT
 * evolve across MPI ranks (evolve_mpi.h; docs/PROTOCOL.md, "Evaluation across processes").
 *
 * Messages (MPI_BYTE copies of the structs below: every rank runs the same build, which the
 * set-up checks, as bit-identical results need anyway):
 *   rank 0 -> worker, TAG_CTRL    ctrlMsg: SETUP (build id, --threads, the resolved config),
 *                                 GO (serve), STOP (exit)
 *   worker -> rank 0, TAG_READY   readyMsg: the protocol was built (or why not), slots, host
 *   slot   -> rank 0, TAG_UP      upMsg: the slot's last result, if any, and "give me a task"
 *   rank 0 -> slot s, TAG_DOWN+s  downMsg: a task, or STOP
 * A slot is one OpenMP thread of a worker; it always has exactly one request outstanding, and
 * rank 0 keeps the requests it cannot serve yet (the generation is handed out) for the next
 * generation, or answers them STOP at the end. */
#define _POSIX_C_SOURCE 200809L
#include "app_common.h"
#include "evolve_mpi.h"

#ifndef ST_WITH_MPI

#include <stdlib.h>

int app_mpi_built(void) { return 0; }

static long env_long(const char *a, const char *b) {
  const char *v = getenv(a) ? getenv(a) : getenv(b);
  return v ? strtol(v, NULL, 10) : -1;
}

/* started as several ranks by a launcher: each would run the whole evolution into the same
 * files, so all refuse (rank 0 says why) */
appMpiRole app_mpi_start(int *argc, char ***argv) {
  (void)argc;
  (void)argv;
  const long size = env_long("OMPI_COMM_WORLD_SIZE", "PMI_SIZE");
  if (size > 1) {
    if (env_long("OMPI_COMM_WORLD_RANK", "PMI_RANK") == 0)
      fprintf(stderr, "evolve: started as %ld MPI ranks, but built without MPI: each would run "
              "the whole evolution into the same files (install OpenMPI, e.g. `make deps`, and "
              "rebuild)\n", size);
    exit(2);
  }
  return APP_MPI_NONE;
}

int app_mpi_serve(void) { return 0; }

const stEvolveEvaluator *app_mpi_evaluator(int threads, const char *out_dir, FILE *progress) {
  (void)threads;
  (void)out_dir;
  (void)progress;
  return NULL;
}

#else

#include <math.h>
#include <mpi.h>
#include <omp.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <time.h> /* nanosleep */
#include <unistd.h>

enum { TAG_CTRL = 1, TAG_READY, TAG_UP, TAG_DOWN = 16 };
enum { CTRL_SETUP = 1, CTRL_GO, CTRL_STOP };
enum { DOWN_TASK = 1, DOWN_STOP };

#define BUILD_ID_MAX 160
/* Waiting is polling with naps that double up to a longest nap: NAP_SHARE of the evaluations'
 * wall time (the delay it can add to an exchange, on average half of it), within [NAP_MIN,
 * NAP_MAX]: about 0.2 ms for simple-prim (2 ms an individual), 2 ms for main-prim (0.4 s), so
 * that a rank that waits costs next to no CPU (rank 0 waits all the time). */
#define NAP_SHARE 0.005
#define NAP_MIN 5e-5
#define NAP_MAX 5e-3
#define POLL_MAX_IDLE 1e-2 /* a worker's longest nap, waiting for the set-up or the go */
#define DEFAULT_TIMEOUT 1800.0

typedef struct ctrlMsg {
  char build[BUILD_ID_MAX]; /* first: readable whatever layout the rest has */
  int kind;
  int threads; /* evolve's --threads, 0 when not given */
  stConfig cfg;
} ctrlMsg;

typedef struct readyMsg {
  int status;  /* building the protocol: stStatus */
  int threads; /* evaluation slots */
  char host[MPI_MAX_PROCESSOR_NAME];
  char err[512];
} readyMsg;

typedef struct upMsg {
  int slot;
  int has_result;
  double cpu, wall; /* the evaluation's thread CPU time and wall time (s) */
  stEvolveResult result;
} upMsg;

typedef struct downMsg {
  int kind;
  stEvolveTask task;
} downMsg;

static int g_rank, g_size, g_thread_level;

int app_mpi_built(void) { return 1; }

static double now(void) { return app_seconds(APP_WALL); }
static double thread_cpu(void) { return app_seconds(APP_THREAD_CPU); }

/* sleeps *delay, then doubles it up to max: waiting costs next to no CPU (OpenMPI's blocking
 * calls spin a core, which other ranks or runs on the node need) */
static void nap(double *delay, double max) {
  struct timespec ts = {0, (long)(*delay * 1e9)};
  nanosleep(&ts, NULL);
  *delay = fmin(2.0 * *delay, max);
}

/* the longest nap while evaluations take wall seconds each */
static double nap_max(double wall) { return fmin(NAP_MAX, fmax(NAP_MIN, NAP_SHARE * wall)); }

static const char *build_id(void) {
  static char id[BUILD_ID_MAX];
  const unsigned one = 1;
  if (!id[0])
    snprintf(id, sizeof id, "selftalk %s evolve-mpi 1, config %zu, task %zu, result %zu bytes, %s",
             ST_VERSION_STRING, sizeof(stConfig), sizeof(stEvolveTask), sizeof(stEvolveResult),
             *(const unsigned char *)&one ? "little-endian" : "big-endian");
  return id;
}

static void mpi_message(int rc, char *buf, int n) {
  char s[MPI_MAX_ERROR_STRING];
  int len = 0;
  if (MPI_Error_string(rc, s, &len) != MPI_SUCCESS) snprintf(s, sizeof s, "error %d", rc);
  snprintf(buf, (size_t)n, "%s", s);
}

/* ================================ worker ranks ================================ */

/* an MPI call failed on a worker: say so once and end the job (rank 0 is told by the launcher) */
static void worker_fail(const char *call, int rc) {
  char s[MPI_MAX_ERROR_STRING];
  mpi_message(rc, s, sizeof s);
  fprintf(stderr, "evolve: MPI rank %d: %s: %s\n", g_rank, call, s);
  MPI_Abort(MPI_COMM_WORLD, 2);
}

#define WCHECK(call)                              \
  do {                                            \
    const int rc_ = (call);                       \
    if (rc_ != MPI_SUCCESS) worker_fail(#call, rc_); \
  } while (0)

typedef struct worker {
  stProtocol *p;
  stIntegratedDef idef;
  stWorkspace *ws; /* one per slot */
  int threads;
  int refused;     /* another build: ends at rank 0's next message */
} worker;

/* rank 0's next control message; *foreign when it comes from another build */
static ctrlMsg *recv_ctrl(int *foreign) {
  MPI_Status s;
  int flag = 0, count = 0;
  for (double d = 1e-4; !flag;) {
    WCHECK(MPI_Iprobe(0, TAG_CTRL, MPI_COMM_WORLD, &flag, &s));
    if (!flag) nap(&d, POLL_MAX_IDLE);
  }
  MPI_Get_count(&s, MPI_BYTE, &count);
  const size_t size = (size_t)count > sizeof(ctrlMsg) ? (size_t)count : sizeof(ctrlMsg);
  ctrlMsg *m = calloc(1, size);
  if (!m) worker_fail("calloc", MPI_ERR_NO_MEM);
  WCHECK(MPI_Recv(m, count, MPI_BYTE, 0, TAG_CTRL, MPI_COMM_WORLD, MPI_STATUS_IGNORE));
  m->build[BUILD_ID_MAX - 1] = 0;
  *foreign = (size_t)count != sizeof(ctrlMsg) || strcmp(m->build, build_id()) != 0;
  return m;
}

static void worker_setup(worker *w, const ctrlMsg *m, int foreign, readyMsg *r) {
  int len = 0;
  memset(r, 0, sizeof *r);
  MPI_Get_processor_name(r->host, &len);
  if (foreign) {
    r->status = ST_ERR_ARG;
    snprintf(r->err, sizeof r->err, "it runs another build of evolve (%s; rank 0: %s)", build_id(),
             m->build);
    w->refused = 1;
    return;
  }
  const int t = st_thread_count(m->threads, &m->cfg);
  w->threads = g_thread_level >= MPI_THREAD_SERIALIZED ? t : 1;
  r->threads = w->threads;
  r->status = st_protocol_create(&m->cfg, &w->p, r->err, sizeof r->err);
  if (r->status) return;
  st_integrated_def_from_config(&m->cfg, &w->idef);
  w->ws = calloc((size_t)w->threads, sizeof *w->ws);
  if (!w->ws) {
    r->status = ST_ERR_NOMEM;
    snprintf(r->err, sizeof r->err, "out of memory");
  }
}

/* waits for this slot's requests, testing them under the lock MPI_THREAD_SERIALIZED asks for;
 * wall: the slot's last evaluation (s), which sets the longest nap */
static void slot_wait(MPI_Request *req, int n, double wall) {
  int done = 0;
  for (double d = 1e-5; !done;) {
#pragma omp critical(st_mpi)
    WCHECK(MPI_Testall(n, req, &done, MPI_STATUSES_IGNORE));
    if (!done) nap(&d, nap_max(wall));
  }
}

/* hands the slot's result (if any) to rank 0 and gets its next task or STOP (non-blocking
 * calls: a blocking one spins while it waits) */
static void slot_exchange(const upMsg *up, downMsg *down) {
  MPI_Request req[2];
#pragma omp critical(st_mpi)
  {
    WCHECK(MPI_Irecv(down, (int)sizeof *down, MPI_BYTE, 0, TAG_DOWN + up->slot, MPI_COMM_WORLD,
                     &req[0]));
    WCHECK(MPI_Isend(up, (int)sizeof *up, MPI_BYTE, 0, TAG_UP, MPI_COMM_WORLD, &req[1]));
  }
  slot_wait(req, 2, up->wall);
}

static void slot_serve(worker *w, int slot) {
  upMsg up;
  downMsg down;
  memset(&up, 0, sizeof up);
  up.slot = slot;
  for (;;) {
    slot_exchange(&up, &down);
    if (down.kind != DOWN_TASK) return;
    const double c0 = thread_cpu(), t0 = now();
    st_evolve_task_run(w->p, &w->idef, &w->ws[slot], &down.task, &up.result);
    up.cpu = thread_cpu() - c0;
    up.wall = now() - t0;
    up.has_result = 1;
  }
}

static void worker_serve(worker *w) {
#pragma omp parallel num_threads(w->threads)
  slot_serve(w, omp_get_thread_num());
}

static void worker_release(worker *w) {
  for (int t = 0; w->ws && t < w->threads; t++) st_workspace_free(&w->ws[t]);
  free(w->ws);
  st_protocol_destroy(w->p);
}

int app_mpi_serve(void) {
  worker w;
  memset(&w, 0, sizeof w);
  for (int done = 0; !done;) {
    int foreign = 0;
    ctrlMsg *m = recv_ctrl(&foreign);
    if (w.refused) {
      done = 1;
    } else if (foreign || m->kind == CTRL_SETUP) {
      readyMsg r;
      worker_setup(&w, m, foreign, &r);
      MPI_Request req;
      WCHECK(MPI_Isend(&r, (int)sizeof r, MPI_BYTE, 0, TAG_READY, MPI_COMM_WORLD, &req));
      slot_wait(&req, 1, 0.0);
    } else {
      if (m->kind == CTRL_GO) worker_serve(&w);
      done = 1;
    }
    free(m);
  }
  worker_release(&w);
  MPI_Finalize();
  return 0;
}

/* ================================ rank 0 ================================ */

enum { C_IDLE = 0, C_SERVING, C_BROKEN };

typedef struct slotRef {
  int rank, slot;
} slotRef;

typedef struct coord {
  int active;       /* MPI runs on this rank 0 */
  int state;        /* C_IDLE: no worker set up; C_SERVING: slots serve; C_BROKEN: abort at exit */
  int threads;      /* --threads, for the workers */
  double timeout;   /* s without any message while tasks are out; 0: wait forever */
  FILE *progress;
  slotRef *pending; /* slots waiting for a task */
  int npending, nslots;
  int *owner;       /* rank evaluating each task of the generation, 0 once answered */
  int nowner;
  /* statistics of the run */
  double *cpu;      /* every evaluation's thread CPU time */
  long ncpu, capcpu;
  double busy;      /* summed wall time of the evaluations */
  double eval_wall; /* rank 0's wall time in evaluate */
  double between;   /* rank 0's wall time from one generation's last result to the next's
                       first task: the GA, the files, the checkpoint */
  double t_end;     /* when the last evaluate returned */
  double cpu_min, cpu_max;
  int generations;
  stEvolveEvaluator ev;
} coord;

static coord g;

static char g_sigmsg[2048];
static size_t g_siglen;
static char g_outdir[1024] = "The output directory";

/* the launcher ends every rank with SIGTERM when one dies, a node is lost, or the job is
 * cancelled: say what that leaves (write() and _exit() only: a signal handler) */
static void on_sigterm(int sig) {
  (void)sig;
  const ssize_t w = write(STDERR_FILENO, g_sigmsg, g_siglen);
  (void)w;
  _exit(2);
}

#define RESUME_NOTE "%s keeps the files of the last finished generation and its checkpoint: the " \
  "same command with --resume continues it, with any number of ranks.\n"

static void set_sigmsg(const char *out_dir) {
  if (out_dir) snprintf(g_outdir, sizeof g_outdir, "%s", out_dir);
  snprintf(g_sigmsg, sizeof g_sigmsg,
           "\nevolve: ended by the MPI launcher (SIGTERM): another rank died, a node was lost, or "
           "the job was cancelled or reached its time limit. " RESUME_NOTE, g_outdir);
  g_siglen = strlen(g_sigmsg);
}

/* rank 0 gives up on the other ranks (its error is printed): MPI_Abort ends them all */
static void coord_abort(void) {
  fprintf(stderr, "evolve: ending every rank (MPI_Abort). " RESUME_NOTE, g_outdir);
  fflush(NULL);
  g_siglen = 0; /* the launcher's SIGTERM that follows needs no second explanation */
  MPI_Abort(MPI_COMM_WORLD, 2);
}

static stStatus coord_fail(const char *what, int rc, char *err, size_t errsz) {
  char s[MPI_MAX_ERROR_STRING];
  mpi_message(rc, s, sizeof s);
  snprintf(err, errsz, "MPI: %s: %s (a rank died or a node was lost?)", what, s);
  g.state = C_BROKEN;
  return ST_ERR_IO;
}

/* the evaluations' mean wall time so far (0 before the first) */
static double mean_wall(void) { return g.ncpu ? g.busy / (double)g.ncpu : 0.0; }

/* how long the other ranks have been silent: a gap in rank 0's own polling (a suspended job)
 * does not count */
typedef struct silence {
  double silent, last;
} silence;

static int too_long(silence *q) {
  const double t = now();
  if (t - q->last < 10.0) q->silent += t - q->last;
  q->last = t;
  return g.timeout > 0 && q->silent > g.timeout;
}

/* the ranks evaluating a task of the generation (the first few) */
static void busy_ranks(char *buf, size_t n) {
  size_t k = 0;
  int shown = 0;
  buf[0] = 0;
  for (int i = 0; i < g.nowner && shown < 8 && k < n; i++) {
    int seen = 0;
    for (int j = 0; j < i; j++) seen |= g.owner[j] == g.owner[i];
    if (!g.owner[i] || seen) continue;
    k += (size_t)snprintf(buf + k, n - k, "%s%d", shown++ ? ", " : " (evaluating: rank ", g.owner[i]);
  }
  if (shown && k < n) snprintf(buf + k, n - k, ")");
}

static stStatus timed_out(const char *what, char *err, size_t errsz) {
  char ranks[128];
  busy_ranks(ranks, sizeof ranks);
  g.state = C_BROKEN;
  snprintf(err, errsz, "MPI: %s for %.0f s%s: a rank hangs or a node is unreachable "
           "(SELFTALK_MPI_TIMEOUT; 0 waits forever)", what, g.timeout, ranks);
  return ST_ERR_IO;
}

/* waits for a message of tag from any rank, or for g.timeout s of silence */
static stStatus wait_message(int tag, MPI_Status *s, char *err, size_t errsz) {
  silence q = {0.0, now()};
  for (double d = 1e-5;;) {
    int flag = 0;
    const int rc = MPI_Iprobe(MPI_ANY_SOURCE, tag, MPI_COMM_WORLD, &flag, s);
    if (rc != MPI_SUCCESS) return coord_fail("MPI_Iprobe", rc, err, errsz);
    if (flag) return ST_OK;
    if (too_long(&q)) return timed_out("no rank answered", err, errsz);
    nap(&d, nap_max(mean_wall()));
  }
}

/* sends and waits until the message is out (a blocking MPI_Send spins, and never returns when
 * the receiver hangs), or for g.timeout s */
static stStatus send_wait(const void *buf, size_t size, int dest, int tag, char *err, size_t errsz) {
  MPI_Request req;
  int rc = MPI_Isend(buf, (int)size, MPI_BYTE, dest, tag, MPI_COMM_WORLD, &req);
  if (rc != MPI_SUCCESS) return coord_fail("MPI_Isend", rc, err, errsz);
  silence q = {0.0, now()};
  for (double d = 1e-5;;) {
    int done = 0;
    if ((rc = MPI_Test(&req, &done, MPI_STATUS_IGNORE)) != MPI_SUCCESS)
      return coord_fail("MPI_Test", rc, err, errsz);
    if (done) return ST_OK;
    if (too_long(&q)) {
      char what[64];
      snprintf(what, sizeof what, "rank %d took no message", dest);
      return timed_out(what, err, errsz);
    }
    nap(&d, nap_max(mean_wall()));
  }
}

static stStatus recv_bytes(void *buf, size_t size, int tag, int *src, char *err, size_t errsz) {
  MPI_Status s;
  stStatus st = wait_message(tag, &s, err, errsz);
  if (st) return st;
  int count = 0;
  MPI_Get_count(&s, MPI_BYTE, &count);
  if ((size_t)count != size) {
    g.state = C_BROKEN;
    snprintf(err, errsz, "MPI: rank %d sent %d bytes where %zu were expected (another build?)",
             s.MPI_SOURCE, count, size);
    return ST_ERR_IO;
  }
  const int rc = MPI_Recv(buf, count, MPI_BYTE, s.MPI_SOURCE, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  if (rc != MPI_SUCCESS) return coord_fail("MPI_Recv", rc, err, errsz);
  *src = s.MPI_SOURCE;
  return ST_OK;
}

static stStatus send_ctrl(int kind, const stConfig *cfg, char *err, size_t errsz) {
  ctrlMsg *m = calloc(1, sizeof *m);
  if (!m) return snprintf(err, errsz, "MPI: out of memory"), ST_ERR_NOMEM;
  snprintf(m->build, sizeof m->build, "%s", build_id());
  m->kind = kind;
  m->threads = g.threads;
  if (cfg) m->cfg = *cfg;
  stStatus st = ST_OK;
  for (int r = 1; r < g_size && !st; r++) {
    st = send_wait(m, sizeof *m, r, TAG_CTRL, err, errsz);
  }
  free(m);
  return st;
}

/* every worker's answer to the set-up; the first refusal (by rank) is the error */
static stStatus collect_ready(readyMsg *ready, char *err, size_t errsz) {
  readyMsg r;
  for (int i = 1; i < g_size; i++) {
    int src = 0;
    stStatus st = recv_bytes(&r, sizeof r, TAG_READY, &src, err, errsz);
    if (st) return st;
    ready[src] = r;
  }
  for (int i = 1; i < g_size; i++)
    if (ready[i].status) {
      snprintf(err, errsz, "MPI rank %d (host %s) cannot evaluate: %s", i, ready[i].host, ready[i].err);
      return (stStatus)ready[i].status;
    }
  return ST_OK;
}

static void print_setup(const readyMsg *ready) {
  if (!g.progress) return;
  int hosts = 0, tmin = ready[1].threads, tmax = ready[1].threads;
  for (int i = 1; i < g_size; i++) {
    int seen = 0;
    for (int j = 1; j < i; j++) seen |= !strcmp(ready[i].host, ready[j].host);
    hosts += !seen;
    tmin = ready[i].threads < tmin ? ready[i].threads : tmin;
    tmax = ready[i].threads > tmax ? ready[i].threads : tmax;
  }
  char th[64], ranks[32];
  if (tmin == tmax) snprintf(th, sizeof th, "%d thread%s each", tmin, tmin == 1 ? "" : "s");
  else snprintf(th, sizeof th, "%d-%d threads each", tmin, tmax);
  if (g_size == 2) snprintf(ranks, sizeof ranks, "rank 1 evaluates");
  else snprintf(ranks, sizeof ranks, "ranks 1-%d evaluate", g_size - 1);
  fprintf(g.progress, "evolve: MPI: %d ranks; rank 0 runs the GA and writes the files, %s (%s: "
          "%d evaluation slot%s on %d host%s)\n", g_size, ranks, th, g.nslots,
          g.nslots == 1 ? "" : "s", hosts, hosts == 1 ? "" : "s");
  fflush(g.progress);
}

/* builds the protocol on every worker from rank 0's resolved config, then lets them serve */
static stStatus coord_setup(const stConfig *cfg, char *err, size_t errsz) {
  readyMsg *ready = calloc((size_t)g_size, sizeof *ready);
  if (!ready) return snprintf(err, errsz, "MPI: out of memory"), ST_ERR_NOMEM;
  stStatus st = send_ctrl(CTRL_SETUP, cfg, err, errsz);
  if (!st) st = collect_ready(ready, err, errsz);
  for (int i = 1; !st && i < g_size; i++) g.nslots += ready[i].threads;
  g.pending = st ? NULL : calloc((size_t)g.nslots, sizeof *g.pending);
  if (!st && !g.pending) st = (snprintf(err, errsz, "MPI: out of memory"), ST_ERR_NOMEM);
  if (!st) st = send_ctrl(CTRL_GO, NULL, err, errsz);
  if (!st) {
    g.state = C_SERVING;
    print_setup(ready);
  }
  free(ready);
  return st;
}

static stStatus send_task(const stEvolveTask *t, char *err, size_t errsz) {
  const slotRef s = g.pending[--g.npending];
  downMsg m;
  memset(&m, 0, sizeof m);
  m.kind = DOWN_TASK;
  m.task = *t;
  g.owner[t->individual] = s.rank;
  return send_wait(&m, sizeof m, s.rank, TAG_DOWN + s.slot, err, errsz);
}

static void record(const upMsg *up) {
  if (g.ncpu == g.capcpu) {
    const long cap = g.capcpu ? 2 * g.capcpu : 1024;
    double *p = realloc(g.cpu, (size_t)cap * sizeof *p);
    if (!p) return;
    g.cpu = p;
    g.capcpu = cap;
  }
  g.cpu[g.ncpu++] = up->cpu;
  g.busy += up->wall;
  g.cpu_min = g.ncpu == 1 || up->cpu < g.cpu_min ? up->cpu : g.cpu_min;
  g.cpu_max = up->cpu > g.cpu_max ? up->cpu : g.cpu_max;
}

/* one slot's message: its result goes in place; the slot waits for a task */
static stStatus take_up(stEvolveResult *results, int n, int *received, char *err, size_t errsz) {
  upMsg up;
  int src = 0;
  stStatus st = recv_bytes(&up, sizeof up, TAG_UP, &src, err, errsz);
  if (st) return st;
  if (up.has_result) {
    const int i = up.result.individual;
    if (i < 0 || i >= n || g.owner[i] != src) {
      g.state = C_BROKEN;
      snprintf(err, errsz, "MPI: rank %d answered genotype %d, which it was not given", src, i);
      return ST_ERR_IO;
    }
    g.owner[i] = 0;
    results[i] = up.result;
    record(&up);
    ++*received;
  }
  if (g.npending >= g.nslots) {
    g.state = C_BROKEN;
    snprintf(err, errsz, "MPI: rank %d asked for more tasks than it has slots", src);
    return ST_ERR_IO;
  }
  g.pending[g.npending].rank = src;
  g.pending[g.npending++].slot = up.slot;
  return ST_OK;
}

static stStatus ensure_owner(int n, char *err, size_t errsz) {
  if (n > g.nowner) {
    int *p = realloc(g.owner, (size_t)n * sizeof *p);
    if (!p) return snprintf(err, errsz, "MPI: out of memory"), ST_ERR_NOMEM;
    g.owner = p;
    g.nowner = n;
  }
  memset(g.owner, 0, (size_t)n * sizeof *g.owner);
  return ST_OK;
}

/* the evaluator: tasks in order to whichever slot asks, until every result is in */
static stStatus coord_evaluate(void *self, const stConfig *cfg, const stEvolveTask *tasks, int n,
                               stEvolveResult *results, char *err, size_t errsz) {
  (void)self;
  stStatus st = g.state == C_IDLE ? coord_setup(cfg, err, errsz) : ST_OK;
  if (!st && g.state != C_SERVING)
    st = (snprintf(err, errsz, "MPI: the workers are lost"), ST_ERR_IO);
  if (!st) st = ensure_owner(n, err, errsz);
  const double t0 = now();
  if (g.generations > 0) g.between += t0 - g.t_end;
  for (int next = 0, received = 0; !st && received < n;) {
    while (!st && next < n && g.npending > 0) st = send_task(&tasks[next++], err, errsz);
    if (!st) st = take_up(results, n, &received, err, errsz);
  }
  g.t_end = now();
  g.eval_wall += g.t_end - t0;
  g.generations++;
  return st;
}

static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static void print_stats(void) {
  if (!g.progress || g.ncpu == 0) return;
  double sum = 0.0;
  for (long i = 0; i < g.ncpu; i++) sum += g.cpu[i];
  qsort(g.cpu, (size_t)g.ncpu, sizeof *g.cpu, cmp_double);
  fprintf(g.progress, "evolve: MPI: %ld evaluations in %d generation%s; CPU per evaluation: mean "
          "%.4g s, min %.4g, median %.4g, max %.4g; the %d slot%s busy %.1f%% of the %.1f s "
          "rank 0 waited for results; rank 0 between generations %.3g s each\n", g.ncpu,
          g.generations, g.generations == 1 ? "" : "s", sum / (double)g.ncpu, g.cpu_min,
          g.cpu[g.ncpu / 2], g.cpu_max, g.nslots, g.nslots == 1 ? " was" : "s were",
          g.eval_wall > 0 ? 100.0 * g.busy / ((double)g.nslots * g.eval_wall) : 0.0, g.eval_wall,
          g.generations > 1 ? g.between / (g.generations - 1) : 0.0);
  fflush(g.progress);
}

/* every slot's request answered STOP: they have all asked once the last generation is in */
static void release_slots(void) {
  char err[512];
  int received = 0;
  while (g.npending < g.nslots)
    if (take_up(NULL, 0, &received, err, sizeof err)) {
      fprintf(stderr, "evolve: %s\n", err);
      coord_abort();
    }
  downMsg m;
  memset(&m, 0, sizeof m);
  m.kind = DOWN_STOP;
  for (int i = 0; i < g.npending; i++)
    if (send_wait(&m, sizeof m, g.pending[i].rank, TAG_DOWN + g.pending[i].slot, err, sizeof err)) {
      fprintf(stderr, "evolve: %s\n", err);
      coord_abort();
    }
}

/* at exit, whatever ended the run: release the workers and finish MPI, or end the job when
 * they cannot be reached */
static void coord_exit(void) {
  if (!g.active) return;
  fflush(NULL);
  if (g.state == C_BROKEN) coord_abort();
  if (g.state == C_SERVING) {
    release_slots();
  } else if (g_size > 1) {
    char err[512];
    if (send_ctrl(CTRL_STOP, NULL, err, sizeof err)) {
      fprintf(stderr, "evolve: %s\n", err);
      coord_abort();
    }
  }
  print_stats();
  free(g.pending);
  free(g.owner);
  free(g.cpu);
  MPI_Finalize();
}

static int launched_by_mpi(void) {
  static const char *vars[] = {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"};
  for (size_t i = 0; i < sizeof vars / sizeof vars[0]; i++)
    if (getenv(vars[i])) return 1;
  return 0;
}

static double env_timeout(void) {
  const char *v = getenv("SELFTALK_MPI_TIMEOUT");
  char *end;
  const double t = v ? strtod(v, &end) : DEFAULT_TIMEOUT;
  return v && (end == v || *end || !(t >= 0)) ? DEFAULT_TIMEOUT : t;
}

appMpiRole app_mpi_start(int *argc, char ***argv) {
  if (!launched_by_mpi()) return APP_MPI_NONE;
  MPI_Init_thread(argc, argv, MPI_THREAD_SERIALIZED, &g_thread_level);
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  MPI_Comm_rank(MPI_COMM_WORLD, &g_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &g_size);
  if (g_rank != 0) return APP_MPI_WORKER;
  g.active = 1;
  g.timeout = env_timeout();
  set_sigmsg(NULL);
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_sigterm;
  sigaction(SIGTERM, &sa, NULL);
  atexit(coord_exit);
  return APP_MPI_COORDINATOR;
}

const stEvolveEvaluator *app_mpi_evaluator(int threads, const char *out_dir, FILE *progress) {
  if (!g.active) return NULL;
  set_sigmsg(out_dir);
  if (g_size < 2) return NULL;
  g.threads = threads;
  g.progress = progress;
  g.ev.evaluate = coord_evaluate;
  g.ev.self = &g;
  return &g.ev;
}

#endif
