/*
 * scene_yaml_read.c -- a scene file read into a light tree with libyaml, so
 * that every field path has a line: anchors and aliases (an alias is a
 * copy of its anchor's node, checked: defined before it, no cycle, a
 * bounded number of copies), keys that are names, one document, nesting
 * limited, and out of memory told apart from a mistake in the file.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <yaml.h>

#include "scene_internal.h"

/* ---- Tree ---------------------------------------------------------------- */

static cti_ynode *ynode_new(int kind, int line)
{
    cti_ynode *n = calloc(1, sizeof *n);
    if (n) {
        n->kind = kind;
        n->line = line;
    }
    return n;
}

void cti_ynode_free(cti_ynode *n)
{
    if (!n)
        return;
    for (int i = 0; i < n->n; i++) {
        cti_ynode_free(n->child[i]);
        if (n->key)
            free(n->key[i]);
    }
    free(n->child);
    free(n->key);
    free(n->key_line);
    free(n->value);
    free(n);
}

static int ynode_push(cti_ynode *p, char *key, int key_line, cti_ynode *c)
{
    if (p->n == p->cap) {
        int cap = p->cap ? 2 * p->cap : 4;
        cti_ynode **ch = realloc(p->child, (size_t)cap * sizeof *ch);
        if (!ch)
            return -1;
        p->child = ch;
        char **k = realloc(p->key, (size_t)cap * sizeof *k);
        if (!k)
            return -1;
        p->key = k;
        int *kl = realloc(p->key_line, (size_t)cap * sizeof *kl);
        if (!kl)
            return -1;
        p->key_line = kl;
        p->cap = cap;
    }
    p->child[p->n] = c;
    p->key[p->n] = key;
    p->key_line[p->n] = key_line;
    p->n++;
    return 0;
}

/* The deepest nesting of sequences and mappings read. A scene needs four
 * levels (interfaces[0].curve[0][0]); the tree is built recursively, so
 * without a limit a file of a million '[' would overflow the stack. */
#define YAML_MAXDEPTH 64

/* Aliases (*name) are read as copies of their anchor's node (&name), which
 * must end before the alias: a node cannot contain an alias of itself, so
 * there are no cycles. A few nested anchors of ten aliases each would make
 * copies of billions of nodes (the "billion laughs"), for the tree and
 * again for libcyaml, which replays the anchor's events: the copies are
 * limited to YAML_MAXCOPY nodes in all and the anchors to YAML_MAXANCHOR
 * (each alias looks its anchor up among them). A scene reuses a material,
 * a curve or a selection a few times: far below either. */
#define YAML_MAXCOPY 100000
#define YAML_MAXANCHOR 1024

typedef struct yanchor {
    char *name;
    cti_ynode *node; /* in the tree, or owned here (an anchored key) when own */
    int own;
    int height;      /* levels of lists and mappings in the node */
    long size;       /* nodes in it */
} yanchor;

typedef struct ybuild {
    yaml_parser_t parser;
    char path[512];
    int depth;
    int err_line;
    int nomem; /* the failure was an allocation's */
    char err[256];
    yanchor *anchor;
    int nanchor, capanchor;
    long copied; /* nodes copied for aliases so far */
} ybuild;

static void set_nomem(ybuild *b)
{
    b->nomem = 1;
    snprintf(b->err, sizeof b->err, "out of memory");
}

static int next_event(ybuild *b, yaml_event_t *ev)
{
    if (!yaml_parser_parse(&b->parser, ev)) {
        const yaml_parser_t *p = &b->parser;
        b->err_line = (int)p->problem_mark.line + 1;
        /* libyaml reports a failed allocation as an error without a
         * problem: not a mistake in the file. */
        if (p->error == YAML_MEMORY_ERROR)
            set_nomem(b);
        else if (p->context)
            snprintf(b->err, sizeof b->err, "malformed YAML: %s %s", p->problem ? p->problem : "error",
                     p->context);
        else
            snprintf(b->err, sizeof b->err, "malformed YAML: %s", p->problem ? p->problem : "error");
        return -1;
    }
    return 0;
}

/* The height (levels of lists and mappings) and the node count of n. */
static void ynode_measure(const cti_ynode *n, int *height, long *size)
{
    int h = 0;
    long s = 1;
    for (int i = 0; i < n->n; i++) {
        int ch;
        long cs;
        ynode_measure(n->child[i], &ch, &cs);
        h = ch > h ? ch : h;
        s += cs;
    }
    *height = n->kind == CTI_Y_SCALAR ? 0 : h + 1;
    *size = s;
}

/* A deep copy of s, or NULL when memory runs out. */
static cti_ynode *ynode_clone(const cti_ynode *s)
{
    cti_ynode *n = ynode_new(s->kind, s->line);
    if (!n)
        return NULL;
    if (s->value && !(n->value = strdup(s->value)))
        goto fail;
    if (s->n > 0) {
        n->child = calloc((size_t)s->n, sizeof *n->child);
        n->key = calloc((size_t)s->n, sizeof *n->key);
        n->key_line = calloc((size_t)s->n, sizeof *n->key_line);
        if (!n->child || !n->key || !n->key_line)
            goto fail;
        n->cap = s->n;
        for (int i = 0; i < s->n; i++) {
            if (!(n->child[i] = ynode_clone(s->child[i])))
                goto fail;
            n->n = i + 1;
            if (s->key && s->key[i] && !(n->key[i] = strdup(s->key[i])))
                goto fail;
            n->key_line[i] = s->key_line ? s->key_line[i] : 0;
        }
    }
    return n;
fail:
    cti_ynode_free(n);
    return NULL;
}

/* Record the anchor `name` of node (complete). Returns 0, or -1 with the
 * error in b. */
static int anchor_add(ybuild *b, const char *name, cti_ynode *node, int own, int line)
{
    if (b->nanchor == YAML_MAXANCHOR) {
        b->err_line = line;
        snprintf(b->err, sizeof b->err, "more than %d anchors (&name), expected fewer",
                 YAML_MAXANCHOR);
        return -1;
    }
    if (b->nanchor == b->capanchor) {
        int cap = b->capanchor ? 2 * b->capanchor : 8;
        yanchor *a = realloc(b->anchor, (size_t)cap * sizeof *a);
        if (!a) {
            set_nomem(b);
            return -1;
        }
        b->anchor = a;
        b->capanchor = cap;
    }
    yanchor *a = &b->anchor[b->nanchor];
    if (!(a->name = strdup(name))) {
        set_nomem(b);
        return -1;
    }
    a->node = node;
    a->own = own;
    ynode_measure(node, &a->height, &a->size);
    b->nanchor++;
    return 0;
}

/* The anchor an alias names (the last one of that name), or NULL with the
 * error in b. */
static const yanchor *anchor_find(ybuild *b, const char *name, int line)
{
    for (int i = b->nanchor - 1; i >= 0; i--)
        if (strcmp(b->anchor[i].name, name) == 0)
            return &b->anchor[i];
    b->err_line = line;
    snprintf(b->err, sizeof b->err,
             "undefined alias *%.60s: expected an anchor &%.60s on a node that ends before it",
             name, name);
    return NULL;
}

static void anchors_free(ybuild *b)
{
    for (int i = 0; i < b->nanchor; i++) {
        free(b->anchor[i].name);
        if (b->anchor[i].own)
            cti_ynode_free(b->anchor[i].node);
    }
    free(b->anchor);
    b->anchor = NULL;
    b->nanchor = b->capanchor = 0;
}

/* The node an alias stands for: a copy of its anchor's. */
static cti_ynode *alias_copy(ybuild *b, const char *name, int line)
{
    const yanchor *a = anchor_find(b, name, line);
    if (!a)
        return NULL;
    b->err_line = line;
    if (b->depth + a->height > YAML_MAXDEPTH) {
        snprintf(b->err, sizeof b->err,
                 "malformed YAML: lists and mappings nested deeper than %d levels (through the "
                 "alias *%.60s)",
                 YAML_MAXDEPTH, name);
        return NULL;
    }
    if (a->size > YAML_MAXCOPY - b->copied) {
        snprintf(b->err, sizeof b->err,
                 "the aliases copy more than %d nodes in all (at *%.60s), expected fewer or "
                 "smaller aliases",
                 YAML_MAXCOPY, name);
        return NULL;
    }
    b->copied += a->size;
    cti_ynode *n = ynode_clone(a->node);
    if (!n)
        set_nomem(b);
    return n;
}

/* The key of a mapping entry whose first event is e (not consumed): a
 * scalar, or an alias of one. NULL with the error in b otherwise. */
static char *read_key(ybuild *b, const yaml_event_t *e, int line)
{
    char *key = NULL;
    if (e->type == YAML_SCALAR_EVENT) {
        if (!(key = strdup((const char *)e->data.scalar.value))) {
            set_nomem(b);
            return NULL;
        }
        if (e->data.scalar.anchor) {
            cti_ynode *k = ynode_new(CTI_Y_SCALAR, line);
            if (!k || !(k->value = strdup(key))) {
                cti_ynode_free(k);
                free(key);
                set_nomem(b);
                return NULL;
            }
            if (anchor_add(b, (const char *)e->data.scalar.anchor, k, 1, line) != 0) {
                cti_ynode_free(k);
                free(key);
                return NULL;
            }
        }
        return key;
    }
    if (e->type == YAML_ALIAS_EVENT) {
        const yanchor *a = anchor_find(b, (const char *)e->data.alias.anchor, line);
        if (!a)
            return NULL;
        if (a->node->kind == CTI_Y_SCALAR) {
            if (!(key = strdup(a->node->value)))
                set_nomem(b);
            return key;
        }
    }
    /* A list or a mapping as a key ("? [a, b]" or "[a]: 1"): the field
     * paths and libcyaml know names only. */
    const char *what = e->type == YAML_SEQUENCE_START_EVENT ? "a list"
                       : e->type == YAML_MAPPING_START_EVENT ? "a mapping"
                                                             : "an alias of a list or mapping";
    b->err_line = line;
    snprintf(b->err, sizeof b->err, "expected a name as the key of a mapping entry, got %s", what);
    return NULL;
}

/* Build the node whose first event is ev (consumed). */
static cti_ynode *build_node(ybuild *b, yaml_event_t *ev)
{
    int line = (int)ev->start_mark.line + 1;
    if (ev->type == YAML_SCALAR_EVENT) {
        cti_ynode *n = ynode_new(CTI_Y_SCALAR, line);
        if (n)
            n->value = strdup((const char *)ev->data.scalar.value);
        if (!n || !n->value) {
            cti_ynode_free(n);
            set_nomem(b);
            n = NULL;
        } else if (ev->data.scalar.anchor &&
                   anchor_add(b, (const char *)ev->data.scalar.anchor, n, 0, line) != 0) {
            cti_ynode_free(n);
            n = NULL;
        }
        yaml_event_delete(ev);
        return n;
    }
    if (ev->type == YAML_ALIAS_EVENT) {
        cti_ynode *n = alias_copy(b, (const char *)ev->data.alias.anchor, line);
        yaml_event_delete(ev);
        return n;
    }
    int seq = ev->type == YAML_SEQUENCE_START_EVENT;
    const yaml_char_t *anchor = seq ? ev->data.sequence_start.anchor : ev->data.mapping_start.anchor;
    char *name = anchor ? strdup((const char *)anchor) : NULL;
    yaml_event_delete(ev);
    if (anchor && !name) {
        set_nomem(b);
        return NULL;
    }
    if (b->depth >= YAML_MAXDEPTH) {
        free(name);
        b->err_line = line;
        snprintf(b->err, sizeof b->err,
                 "malformed YAML: lists and mappings nested deeper than %d levels",
                 YAML_MAXDEPTH);
        return NULL;
    }
    cti_ynode *n = ynode_new(seq ? CTI_Y_SEQ : CTI_Y_MAP, line);
    if (!n) {
        free(name);
        set_nomem(b);
        return NULL;
    }
    b->depth++;
    size_t plen = strlen(b->path);
    for (;;) {
        yaml_event_t e;
        if (next_event(b, &e) != 0)
            goto fail;
        if (e.type == YAML_SEQUENCE_END_EVENT || e.type == YAML_MAPPING_END_EVENT) {
            yaml_event_delete(&e);
            break;
        }
        char *key = NULL;
        int key_line = (int)e.start_mark.line + 1;
        if (seq) {
            snprintf(b->path + plen, sizeof b->path - plen, "[%d]", n->n);
        } else {
            key = read_key(b, &e, key_line);
            yaml_event_delete(&e);
            if (!key)
                goto fail;
            snprintf(b->path + plen, sizeof b->path - plen, "%s%s", plen ? "." : "", key);
            if (next_event(b, &e) != 0) {
                free(key);
                goto fail;
            }
        }
        cti_ynode *c = build_node(b, &e);
        if (!c || ynode_push(n, key, key_line, c) != 0) {
            if (c)
                set_nomem(b);
            free(key);
            cti_ynode_free(c);
            goto fail;
        }
        b->path[plen] = '\0';
    }
    b->depth--;
    /* The anchor names the node once it is complete: an alias inside it
     * finds no anchor (a cycle is an undefined alias). */
    if (name && anchor_add(b, name, n, 0, line) != 0) {
        free(name);
        cti_ynode_free(n);
        return NULL;
    }
    free(name);
    return n;
fail:
    b->depth--;
    free(name);
    cti_ynode_free(n);
    return NULL;
}

/* An empty plain scalar without anchor or tag: what libyaml reads for a
 * document with no content ("---" alone). */
static int empty_document(const yaml_event_t *e)
{
    return e->type == YAML_SCALAR_EVENT && e->data.scalar.length == 0 &&
           e->data.scalar.style == YAML_PLAIN_SCALAR_STYLE && !e->data.scalar.anchor &&
           !e->data.scalar.tag;
}

cti_ynode *cti_yaml_read(const char *path, int *code, int *line, char *field, size_t fieldlen,
                         char *msg, size_t msglen)
{
    *code = CT_ERR_ARG;
    *line = 0;
    field[0] = '\0';
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(msg, msglen, "cannot open the scene file: %s", strerror(errno));
        return NULL;
    }
    struct stat st;
    if (fstat(fileno(f), &st) == 0 && S_ISDIR(st.st_mode)) {
        fclose(f); /* libyaml said "input error" */
        snprintf(msg, msglen, "cannot read the scene file: it is a directory");
        return NULL;
    }
    ybuild b;
    memset(&b, 0, sizeof b);
    if (!yaml_parser_initialize(&b.parser)) {
        fclose(f);
        *code = CT_ERR_NOMEM;
        snprintf(msg, msglen, "out of memory (cannot initialise libyaml)");
        return NULL;
    }
    yaml_parser_set_input_file(&b.parser, f);
    cti_ynode *root = NULL;
    yaml_event_t e;
    int ok = 1, ndoc = 0;
    /* Stream start, document start, the root node, document end. */
    while (ok) {
        if (next_event(&b, &e) != 0) {
            ok = 0;
            break;
        }
        if (e.type == YAML_STREAM_END_EVENT) {
            yaml_event_delete(&e);
            break;
        }
        if (e.type == YAML_DOCUMENT_START_EVENT && ++ndoc > 1) {
            /* libcyaml reads the first document only: what follows would
             * be ignored without a word. */
            b.err_line = (int)e.start_mark.line + 1;
            snprintf(b.err, sizeof b.err,
                     "a second YAML document (after '---' or '...'): expected one scene per file");
            yaml_event_delete(&e);
            ok = 0;
            break;
        }
        if (empty_document(&e) && !root) {
            yaml_event_delete(&e);
            continue;
        }
        if (e.type == YAML_SCALAR_EVENT || e.type == YAML_SEQUENCE_START_EVENT ||
            e.type == YAML_MAPPING_START_EVENT || e.type == YAML_ALIAS_EVENT) {
            root = build_node(&b, &e);
            if (!root)
                ok = 0;
            continue;
        }
        yaml_event_delete(&e);
    }
    yaml_parser_delete(&b.parser);
    anchors_free(&b);
    fclose(f);
    if (!ok) {
        cti_ynode_free(root);
        if (b.nomem || !b.err[0]) {
            *code = CT_ERR_NOMEM;
            snprintf(msg, msglen, "out of memory reading the scene file");
            return NULL;
        }
        *line = b.err_line;
        snprintf(field, fieldlen, "%s", b.path);
        snprintf(msg, msglen, "%s", b.err);
        return NULL;
    }
    if (!root) {
        *line = 1;
        snprintf(msg, msglen,
                 "the file holds no YAML content (it is empty, or only comments, blank lines and "
                 "'---'), expected a mapping with end_time, mesh, parts");
        return NULL;
    }
    return root;
}
