/*
 * bench_real.c -- the search benchmarks on real meshes: the four searches
 * (direct, topological, bucket, bsp) on the Radioss decks of
 * $CT_SHARED/data/radioss/ (read in place, never copied: see that folder's
 * NOTICE.md) and on any deck named by CT_BENCH_MESH (`make bench MESH=path`).
 *
 * The query is self contact over all shell segments of the deck (/SHELL and
 * /SH3N; a deck without shells uses the brick faces its surfaces define):
 * the main segments are those shells, the secondary nodes every node used by
 * them, self = 1 (a node never pairs with a segment it belongs to). The
 * search distance follows the synthetic families (bench_search.c): with h
 * the mean edge length of the main segments (each segment's edges, a
 * triangle's three, an edge shared by two segments counted twice, as
 * meshgen computes it), gap = 0.3 h and margin = 0.2 h, so gap + margin =
 * 0.5 h.
 *
 * Names: real/<deck>/<algo>/t<threads> (<deck>: the file name without its
 * extension; Google Benchmark appends "/real_time"). The conventions are the
 * search benchmark's: the deck is read once and kept while its benchmarks
 * run (they are registered next to each other), its arrays are first-touch
 * copies made by the largest team, each run binds its threads, runs one
 * untimed search (workspace growth; the topological search's full first
 * search), then times whole searches. Counters: ns_per_node, nsec, nseg,
 * pairs, bytes_per_node (workspace / secondary nodes), threads, and for the
 * topological search misses (pairs of the reference it does not report;
 * the reference is direct, or bucket when direct is over its budget).
 */
#include "bench_real.h"

#include "bench_common.h"

#include <glob.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "bench_topology.h"
#include "contact.h"
#include "gbench.h"
#include "import_radioss.h"

/* ---- What a benchmark is ------------------------------------------------ */

typedef struct real_desc {
    char path[1024];
    char deck[96];
    ct_search_algo algo;
    int threads;
    struct real_desc *next; /* registration list, freed at the end */
} real_desc;

static real_desc *descs;
static ctb_search_config cfg;

/* ---- The deck cache (one deck at a time) -------------------------------- */

typedef struct real_mesh {
    int valid; /* 1: read (or failed: rc != 0) for path */
    int rc;
    char err[1400];
    char path[1024];
    const char *segkind; /* "shells" or "brick faces" */
    ctb_mesh m; /* first-touched copies of the search input, the reference */
    double h_mean;
} real_mesh;

static real_mesh cur;

static void mesh_clear(real_mesh *m)
{
    ctb_mesh_clear(&m->m);
    memset(m, 0, sizeof *m);
}

static int is_shell(int8_t kind) { return kind == CTD_SEG_SHELL || kind == CTD_SEG_SH3N; }

/* The mean edge length of the selected segments (see the top of the file). */
static double mean_edge(const ct_mesh *m, const ct_idx *n1, const ct_idx *n2, const ct_idx *n3,
                        const ct_idx *n4, ct_idx nseg)
{
    const ct_real *x = m->nodes.x, *y = m->nodes.y, *z = m->nodes.z;
    double sum = 0;
    int64_t cnt = 0;
    for (ct_idx s = 0; s < nseg; s++) {
        ct_idx v[4] = {n1[s], n2[s], n3[s], n4[s]};
        for (int e = 0; e < 4; e++) {
            ct_idx p = v[e], q = v[(e + 1) & 3];
            if (p == q)
                continue;
            double dx = (double)x[q] - (double)x[p], dy = (double)y[q] - (double)y[p],
                   dz = (double)z[q] - (double)z[p];
            sum += sqrt(dx * dx + dy * dy + dz * dz);
            cnt++;
        }
    }
    return cnt > 0 ? sum / (double)cnt : 0.0;
}

/* The search input of a deck: its shell segments (or, without shells, all
 * its segments) and the nodes they use, in increasing node order. */
static int deck_input(const ctd_deck *deck, real_mesh *m)
{
    const ct_mesh *me = &deck->mesh;
    ct_idx nshell = 0;
    for (ct_idx s = 0; s < me->nseg; s++)
        nshell += is_shell(deck->seg_kind[s]);
    int all = nshell == 0;
    ct_idx nseg = all ? me->nseg : nshell;
    m->segkind = all ? "brick faces" : "shells";
    if (nseg == 0) {
        snprintf(m->err, sizeof m->err, "deck %s: no shell segments and no surface faces",
                 m->path);
        return CT_ERR_ARG;
    }
    ct_idx nn = me->nodes.n;
    ct_idx *t1 = malloc((size_t)nseg * sizeof *t1), *t2 = malloc((size_t)nseg * sizeof *t2);
    ct_idx *t3 = malloc((size_t)nseg * sizeof *t3), *t4 = malloc((size_t)nseg * sizeof *t4);
    ct_idx *ts = malloc(((size_t)nn + 1) * sizeof *ts);
    unsigned char *used = calloc((size_t)nn + 1, 1);
    int rc = CT_OK;
    if (!t1 || !t2 || !t3 || !t4 || !ts || !used) {
        rc = CT_ERR_NOMEM;
        goto done;
    }
    ct_idx k = 0;
    for (ct_idx s = 0; s < me->nseg; s++) {
        if (!all && !is_shell(deck->seg_kind[s]))
            continue;
        t1[k] = me->n1[s];
        t2[k] = me->n2[s];
        t3[k] = me->n3[s];
        t4[k] = me->n4[s];
        used[t1[k]] = used[t2[k]] = used[t3[k]] = used[t4[k]] = 1;
        k++;
    }
    ct_idx nsec = 0;
    for (ct_idx i = 0; i < nn; i++)
        if (used[i])
            ts[nsec++] = i;
    m->h_mean = mean_edge(me, t1, t2, t3, t4, nseg);

    ct_search_input in;
    memset(&in, 0, sizeof in);
    in.nnode = nn;
    in.x = me->nodes.x;
    in.y = me->nodes.y;
    in.z = me->nodes.z;
    in.nsec = nsec;
    in.sec = ts;
    in.nseg = nseg;
    in.n1 = t1;
    in.n2 = t2;
    in.n3 = t3;
    in.n4 = t4;
    double gap, margin;
    ctb_search_gap(m->h_mean, &gap, &margin);
    in.gap = (ct_real)gap;
    in.margin = (ct_real)margin;
    in.self = 1;
    in.filter = CT_FILTER_HULL;
    /* First-touch copies made by the largest team the runs use. */
    rc = ctb_mesh_copy(&m->m, &in, cfg.bind, cfg.max_threads);
done:
    if (rc == CT_ERR_NOMEM)
        snprintf(m->err, sizeof m->err, "deck %s: %s", m->path, ct_strerror(rc));
    free(t1);
    free(t2);
    free(t3);
    free(t4);
    free(ts);
    free(used);
    return rc;
}

/* Read the deck of d (or keep it when it is the current one). */
static real_mesh *mesh_get(const real_desc *d)
{
    if (cur.valid && strcmp(cur.path, d->path) == 0)
        return &cur;
    mesh_clear(&cur);
    cur.valid = 1;
    snprintf(cur.path, sizeof cur.path, "%s", d->path);
    ctd_deck deck;
    ct_diag diag;
    memset(&deck, 0, sizeof deck);
    memset(&diag, 0, sizeof diag);
    int rc = ctd_deck_read(d->path, &deck, &diag);
    if (rc != CT_OK) {
        cur.rc = rc;
        snprintf(cur.err, sizeof cur.err, "deck: %s: %s", ct_strerror(rc), diag.msg);
        return &cur;
    }
    cur.rc = deck_input(&deck, &cur);
    ctd_deck_destroy(&deck);
    return &cur;
}

/* ---- The benchmark ------------------------------------------------------- */

static void bm_real(gb_state *st, void *arg)
{
    const real_desc *d = arg;
    real_mesh *m = mesh_get(d);
    if (m->rc != CT_OK) {
        gb_skip_with_error(st, m->err);
        return;
    }
    char prefix[64];
    snprintf(prefix, sizeof prefix, "self %s ", m->segkind);
    ctb_search_bench(st, &m->m, &cfg, d->algo, d->threads, m->h_mean, prefix);
}

/* ---- Registration -------------------------------------------------------- */

/* The deck's name: the file name without directory and extension, with any
 * character other than letters, digits, '_', '-' and '.' replaced by '_'. */
static void deck_name(const char *path, char *name, size_t len)
{
    const char *b = strrchr(path, '/');
    b = b ? b + 1 : path;
    snprintf(name, len, "%s", b);
    char *dot = strrchr(name, '.');
    if (dot && dot != name)
        *dot = '\0';
    for (char *c = name; *c; c++)
        if (!((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') ||
              *c == '_' || *c == '-' || *c == '.'))
            *c = '_';
}

static int add_deck(const char *path)
{
    int tlist[2] = {1, cfg.max_threads};
    int nt = cfg.max_threads > 1 ? 2 : 1;
    int count = 0;
    for (int a = 0; a < CT_SEARCH_NALGO; a++)
        for (int t = 0; t < nt; t++) {
            real_desc *d = calloc(1, sizeof *d);
            if (!d)
                return -1;
            snprintf(d->path, sizeof d->path, "%s", path);
            deck_name(path, d->deck, sizeof d->deck);
            d->algo = (ct_search_algo)a;
            d->threads = tlist[t];
            d->next = descs;
            descs = d;
            char name[160];
            snprintf(name, sizeof name, "real/%s/%s/t%d", d->deck, ct_search_algo_name(d->algo),
                     d->threads);
            if (gb_register(name, bm_real, d, -1, 1, 0, 0) != 0)
                return -1;
            count++;
        }
    return count;
}

int ctb_real_register(const ctb_search_config *c)
{
    cfg = *c;
    if (cfg.max_threads < 1)
        cfg.max_threads = 1;
    int count = 0;
    const char *shared = getenv("CT_SHARED");
    if (!shared || !*shared)
        shared = "../shared";
    char dir[1024], pattern[1100];
    snprintf(dir, sizeof dir, "%s/data/radioss", shared);
    snprintf(pattern, sizeof pattern, "%s/*.rad", dir);
    struct stat sb;
    if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode)) {
        printf("# real meshes: %s not found (set CT_SHARED to the shared folder): the Radioss "
               "decks are skipped\n",
               dir);
    } else {
        glob_t g;
        memset(&g, 0, sizeof g);
        int grc = glob(pattern, 0, NULL, &g);
        if (grc == GLOB_NOSPACE) {
            globfree(&g);
            return -1;
        }
        if (grc != 0 || g.gl_pathc == 0)
            printf("# real meshes: no *.rad deck in %s: skipped\n", dir);
        for (size_t i = 0; grc == 0 && i < g.gl_pathc; i++) {
            int k = add_deck(g.gl_pathv[i]);
            if (k < 0) {
                globfree(&g);
                return -1;
            }
            printf("# real mesh: %s\n", g.gl_pathv[i]);
            count += k;
        }
        globfree(&g);
    }
    const char *mesh = getenv("CT_BENCH_MESH");
    if (mesh && *mesh) {
        int k = add_deck(mesh);
        if (k < 0)
            return -1;
        printf("# real mesh (CT_BENCH_MESH): %s\n", mesh);
        count += k;
    }
    if (count > 0)
        printf("# real meshes: self contact over the shell segments, secondary = their nodes, "
               "gap = 0.3 h, margin = 0.2 h (h: mean edge length of the shells)\n");
    fflush(stdout);
    return count;
}

void ctb_real_cleanup(void)
{
    mesh_clear(&cur);
    while (descs) {
        real_desc *n = descs->next;
        free(descs);
        descs = n;
    }
}
